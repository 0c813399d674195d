// The triangle of docs/thresholds.md: contact on (0,0)-(1,0), free hypotenuse, clamped left
// side; its ends are a contact-clamped corner of 90 degrees at (0,0) and a contact-free corner
// of 45 degrees at (1,0).
Point(1) = {0, 0, 0, 1}; Point(2) = {1, 0, 0, 1}; Point(3) = {0, 1, 0, 1};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 1};
Curve Loop(1) = {1, 2, 3}; Plane Surface(1) = {1};
Physical Curve("contact") = {1}; Physical Curve("free") = {2}; Physical Curve("clamped") = {3};
Physical Surface("body") = {1};
