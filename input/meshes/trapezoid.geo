// SPDX-License-Identifier: MIT
// A trapezoid for the example study (input/studies/study_example.nml): bottom 0..2 at
// y = 0 (group bottom, in contact), top 0.5..1.5 at y = 1 (group top, fixed), slanted free
// sides right and left; the body of the trapezoid scene of tests/data/truths.csv without
// its grading (the hp levels grade the mesh themselves). Element size from the command
// line, e.g.
//   gmsh input/meshes/trapezoid.geo -2 -order 1 -clmax 0.5 -format msh41 -o trapezoid.msh
Point(1) = {0, 0, 0, 1};
Point(2) = {2, 0, 0, 1};
Point(3) = {1.5, 1, 0, 1};
Point(4) = {0.5, 1, 0, 1};
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
