// A half ball of radius R = 10 (scenes/hertz.opts): the lower hemisphere of the ball centred at (0, 0, R), its pole
// at the origin touching the plane z = 0, its flat face "top" at z = R. The spherical surface is split at z = 0.25
// into the "cap" around the pole (radius 2.22, where contact happens: the contact radius is about 1) and the
// "side". The mesh is refined towards the pole: size 0.2/L within 1.5 of it, growing by 0.3 per unit of distance
// beyond, at most 2.
If (!Exists(L))
  L = 2;
EndIf
R  = 10;
zc = 0.25;
SetNumber("ssstar/nodes", 2200 * L^3);   // measured: 2243, 8855, 23614, 50096 nodes for L = 1..4
SetFactory("OpenCASCADE");
Sphere(1) = {0, 0, R, R, -Pi/2, 0, 2*Pi};
Box(2) = {-R, -R, -1, 2*R, 2*R, 1 + zc};
cap() = BooleanIntersection{ Volume{1}; }{ Volume{2}; Delete; };
Box(3) = {-R, -R, zc, 2*R, 2*R, R + 1};
upper() = BooleanIntersection{ Volume{1}; Delete; }{ Volume{3}; Delete; };
parts() = BooleanFragments{ Volume{cap(), upper()}; Delete; }{};
lower() = Volume In BoundingBox{-R, -R, -0.1, R, R, zc + 0.1};
capFaces() = Boundary{ Volume{lower()}; };
otherFaces() = Boundary{ Volume{parts()}; };
otherFaces() -= capFaces();
capFaces() -= Surface In BoundingBox{-R, -R, zc - 0.01, R, R, zc + 0.01};     // the inner disk at z = zc
top() = Surface In BoundingBox{-R - 0.1, -R - 0.1, R - 0.1, R + 0.1, R + 0.1, R + 0.1};
otherFaces() -= top();
Physical Volume("ball") = {parts()};
Physical Surface("cap") = {capFaces()};
Physical Surface("side") = {otherFaces()};
Physical Surface("top") = {top()};
Field[1] = MathEval;
Field[1].F = Sprintf("Min(2, %g + 0.3 * Max(0, Sqrt(x*x + y*y + z*z) - 1.5))", 0.2 / L);
Background Field = 1;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;
