// SPDX-License-Identifier: MIT
// input/meshes/half_contact.geo with the grading of rectangle.geo (docs/accuracy.md,
// "Independent truths"): unit square, contact on the left half of the bottom, the right
// half (bottom_free) traction-free like the sides, top fixed. Graded toward both ends of
// Gamma_C (0,0) and (1/2,0), the top corners and the free corner (1,0).
DefineConstant[ graded = 1, alpha = 0.2, hmin = 1e-4, hmax = 0.1, algorithm = 5 ];
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
If (graded == 1)
    Field[1] = Distance;
    Field[1].PointsList = {1, 2, 3, 4, 5};
    Field[2] = MathEval;
    Field[2].F = Sprintf("min(%.17g, max(%.17g, %.17g * F1))", hmax, hmin, alpha);
    Background Field = 2;
    Mesh.MeshSizeExtendFromBoundary = 0;
    Mesh.MeshSizeFromPoints = 0;
    Mesh.MeshSizeFromCurvature = 0;
EndIf
Mesh.Algorithm = algorithm;   // 5 Delaunay (default), 6 Frontal-Delaunay, 1 MeshAdapt
