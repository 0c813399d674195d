// SPDX-License-Identifier: MIT
// Trapezoid of the independent truths (docs/accuracy.md, "Independent truths"): bottom
// 0..2 at y = 0 (group bottom, contact), top 0.5..1.5 at y = 1 (group top, fixed), slanted
// free sides right and left. Grading as in rectangle.geo (toward the four corners).
DefineConstant[ graded = 1, alpha = 0.2, hmin = 1e-4, hmax = 0.1, algorithm = 5 ];
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
