// SPDX-License-Identifier: MIT
// The unit square with contact on the left half of the bottom only: top fixed ("top"), the
// right half of the bottom and both sides traction-free ("free"), contact on [0, 0.5] x {0}
// ("contact"). A coarse start for adaptive runs (scripts/estimate_quality.sh):
//   gmsh input/meshes/half_contact.geo -2 -clmax 0.25 -format msh41 -o half_contact.msh
// with -order 2 or -order 3 for 6- or 10-node triangles.
Point(1) = {0, 0, 0, 1};
Point(2) = {0.5, 0, 0, 1};
Point(3) = {1, 0, 0, 1};
Point(4) = {1, 1, 0, 1};
Point(5) = {0, 1, 0, 1};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 5};
Line(5) = {5, 1};
Curve Loop(1) = {1, 2, 3, 4, 5};
Plane Surface(1) = {1};
Physical Curve("contact") = {1};
Physical Curve("free") = {2, 3, 5};
Physical Curve("top") = {4};
Physical Surface("body") = {1};
