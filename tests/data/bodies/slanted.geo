// The four-sided body with a slanted clamped top of docs/thresholds.md: contact on
// (0,0)-(1.5,0), left and right free; both ends are contact-free corners of 90 degrees.
Point(1) = {0, 0, 0, 1}; Point(2) = {1.5, 0, 0, 1}; Point(3) = {1.5, 0.7, 0, 1}; Point(4) = {0, 1, 0, 1};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
Physical Curve("contact") = {1}; Physical Curve("right") = {2}; Physical Curve("top") = {3}; Physical Curve("left") = {4};
Physical Surface("body") = {1};
