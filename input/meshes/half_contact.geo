// SPDX-License-Identifier: MIT
// The reference square with contact on the left half of the bottom only: the right half,
// 'bottom_free', is traction-free like the sides. Gmsh's Delaunay algorithm; the element size
// comes from the command line, for instance (input/half_contact.nml uses h = 1/16, order 2)
//   gmsh input/meshes/half_contact.geo -2 -order 2 -clmax 0.0625 -format msh41 \
//       -o input/meshes/half_contact_16.msh
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
Physical Curve("bottom_free") = {2};
Physical Curve("right") = {3};
Physical Curve("top") = {4};
Physical Curve("left") = {5};
Physical Surface("body") = {1};
Mesh.Algorithm = 5;   // Delaunay
