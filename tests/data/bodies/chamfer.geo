// The chamfered block of issue 34: contact on (0,0)-(1.7,0), top clamped, left, right and
// chamfer free; its ends are contact-free corners of 90 degrees at (0,0) and 135 at (1.7,0).
Point(1) = {0, 0, 0, 1}; Point(2) = {1.7, 0, 0, 1}; Point(3) = {2, 0.3, 0, 1};
Point(4) = {2, 1, 0, 1}; Point(5) = {0, 1, 0, 1};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 5}; Line(5) = {5, 1};
Curve Loop(1) = {1, 2, 3, 4, 5}; Plane Surface(1) = {1};
Physical Curve("contact") = {1}; Physical Curve("chamfer") = {2}; Physical Curve("right") = {3};
Physical Curve("top") = {4}; Physical Curve("left") = {5}; Physical Surface("body") = {1};
