// Hertz between two elastic bodies (scenes/hertz2.opts): the half ball of meshes/hertz.geo (radius R = 10, pole at
// the origin, "cap" around the pole, "side", flat "top" at z = R; volume "ball") resting on a block 20 x 20 x 10
// below z = 0 (volume "block", faces "block_top" at z = 0 and "block_bottom" at z = -10). The two volumes touch at
// the pole only and are meshed apart (not fused). Both are refined towards the pole: size 0.2/L within 1.5 of it,
// growing by 0.3 per unit of distance beyond, at most 2.
If (!Exists(L))
  L = 1;
EndIf
R  = 10;
zc = 0.25;
SetNumber("ssstar/nodes", 4000 * L^3);
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
Box(10) = {-R, -R, -R, 2*R, 2*R, R};
b[] = Abs(Boundary{ Volume{10}; }); // OpenCASCADE's box faces: x = min, max, y = min, max, z = min, max
Physical Volume("ball") = {parts()};
Physical Surface("cap") = {capFaces()};
Physical Surface("side") = {otherFaces()};
Physical Surface("top") = {top()};
Physical Volume("block") = {10};
Physical Surface("block_top") = {b[5]};
Physical Surface("block_bottom") = {b[4]};
Field[1] = MathEval;
Field[1].F = Sprintf("Min(2, %g + 0.3 * Max(0, Sqrt(x*x + y*y + z*z) - 1.5))", 0.2 / L);
Background Field = 1;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;
