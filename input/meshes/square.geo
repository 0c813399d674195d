// SPDX-License-Identifier: MIT
// The reference scene of model.md section 10: the unit square, with the physical groups that
// input/delaunay.nml names. Gmsh's Delaunay algorithm; the element size h comes from the
// command line (the point sizes below are larger than any h used), for instance
//   gmsh input/meshes/square.geo -2 -clmax 0.0625 -format msh41 -o square.msh
// and -order 2 for 6-node triangles. scripts/make_mesh.sh wraps this.
Point(1) = {0, 0, 0, 1};
Point(2) = {1, 0, 0, 1};
Point(3) = {1, 1, 0, 1};
Point(4) = {0, 1, 0, 1};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Physical Curve("bottom") = {1};
Physical Curve("right") = {2};
Physical Curve("top") = {3};
Physical Curve("left") = {4};
Physical Surface("body") = {1};
Mesh.Algorithm = 5;   // Delaunay
