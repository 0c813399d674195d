// SPDX-License-Identifier: MIT
// W x H rectangle of the independent truths (docs/accuracy.md, "Independent truths"):
// groups bottom (contact), right, top (fixed), left. With graded = 1 (default) the cell
// size is h(r) = min(hmax, max(hmin, alpha r)), r the distance to the nearest corner (the
// ends of Gamma_C and the corners where the fixed top meets a free side): a geometric
// grading toward the singular points. With graded = 0 Gmsh's plain Delaunay mesh of size
// -clmax. Parameters from the command line, e.g.
//   gmsh rectangle.geo -setnumber W 3 -setnumber alpha 0.2 -setnumber hmin 1e-5 \
//        -setnumber hmax 0.1 -2 -order 4 -format msh41 -o mesh.msh
DefineConstant[ W = 1, H = 1, graded = 1, alpha = 0.2, hmin = 1e-4, hmax = 0.1, algorithm = 5 ];
Point(1) = {0, 0, 0, 1};
Point(2) = {W, 0, 0, 1};
Point(3) = {W, H, 0, 1};
Point(4) = {0, H, 0, 1};
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
If (graded == 1)
    Field[1] = Distance;
    Field[1].PointsList = {1, 2, 3, 4};
    Field[2] = MathEval;
    Field[2].F = Sprintf("min(%.17g, max(%.17g, %.17g * F1))", hmax, hmin, alpha);
    Background Field = 2;
    Mesh.MeshSizeExtendFromBoundary = 0;
    Mesh.MeshSizeFromPoints = 0;
    Mesh.MeshSizeFromCurvature = 0;
EndIf
Mesh.Algorithm = algorithm;   // 5 Delaunay (default), 6 Frontal-Delaunay, 1 MeshAdapt
