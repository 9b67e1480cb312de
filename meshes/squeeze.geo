// A ball of radius R = 10 between two plates (scenes/squeeze.opts): centred at (0, 0, R), its poles at the origin
// (touching the plane z = 0) and at (0, 0, 2R) (touching the plane z = 2R). The sphere is split at z = 0.25 and at
// z = 2R - 0.25 into the caps around the poles, "bottom_cap" and "top_cap" (radius 2.22, where contact happens), and
// the "side". The mesh is refined towards both poles: size 0.2/L within 1.5 of a pole, growing by 0.3 per unit of
// distance beyond, at most 2.
If (!Exists(L))
  L = 1;
EndIf
R  = 10;
zc = 0.25;
SetNumber("ssstar/nodes", 4400 * L^3);   // measured: 4512, 17637 nodes for L = 1, 2
SetFactory("OpenCASCADE");
Sphere(1) = {0, 0, R, R};
Box(2) = {-R - 1, -R - 1, -1, 2*R + 2, 2*R + 2, 1 + zc};
Box(3) = {-R - 1, -R - 1, zc, 2*R + 2, 2*R + 2, 2*R - 2*zc};
Box(4) = {-R - 1, -R - 1, 2*R - zc, 2*R + 2, 2*R + 2, zc + 1};
lower() = BooleanIntersection{ Volume{1}; }{ Volume{2}; Delete; };
middle() = BooleanIntersection{ Volume{1}; }{ Volume{3}; Delete; };
upper() = BooleanIntersection{ Volume{1}; Delete; }{ Volume{4}; Delete; };
parts() = BooleanFragments{ Volume{lower(), middle(), upper()}; Delete; }{};
e = 0.01;
bottom() = Surface In BoundingBox{-R, -R, -e, R, R, zc + e};
bottom() -= Surface In BoundingBox{-R, -R, zc - e, R, R, zc + e};          // the inner disk at z = zc
top() = Surface In BoundingBox{-R, -R, 2*R - zc - e, R, R, 2*R + e};
top() -= Surface In BoundingBox{-R, -R, 2*R - zc - e, R, R, 2*R - zc + e}; // the inner disk at z = 2R - zc
side() = Surface In BoundingBox{-R - e, -R - e, zc - e, R + e, R + e, 2*R - zc + e};
side() -= Surface In BoundingBox{-R, -R, zc - e, R, R, zc + e};
side() -= Surface In BoundingBox{-R, -R, 2*R - zc - e, R, R, 2*R - zc + e};
Physical Volume("ball") = {parts()};
Physical Surface("bottom_cap") = {bottom()};
Physical Surface("top_cap") = {top()};
Physical Surface("side") = {side()};
Field[1] = MathEval;
Field[1].F = Sprintf("Min(2, %g + 0.3 * Max(0, Min(Sqrt(x*x + y*y + z*z), Sqrt(x*x + y*y + (z - %g)*(z - %g))) - 1.5))", 0.2 / L, 2*R, 2*R);
Background Field = 1;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;
