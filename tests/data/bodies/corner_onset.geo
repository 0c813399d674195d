// Body 28 of scripts/dev/random_bodies.sh -s 35 -n 29 (docs/accuracy.md, "A second seed"):
// contact on 2-3, its end at 3 an 86.3-degree corner beside a free side whose crossing
// (lambda = 1.57728) lambda+ = 1.5821 lies just past; the onset of lambda+ is a collision.
Point(1) = {1.97771719177, 1.35590180081, 0, 1};
Point(2) = {1.17476403616, 1.5962525524, 0, 1};
Point(3) = {0, 1.4992225884, 0, 1};
Point(4) = {0.220375221002, 0.0156120654993, 0, 1};
Point(5) = {1.33621091234, 0, 0, 1};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 5};
Line(5) = {5, 1};
Curve Loop(1) = {1, 2, 3, 4, 5};
Plane Surface(1) = {1};
Physical Curve("contact") = {2};
Physical Curve("clamped") = {4};
Physical Curve("free") = {1, 3, 5};
Physical Surface("body") = {1};
