// A block 10 x 10 x 5 (x, y in (-5, 5), z in (-5, 0)) whose top face z = 0 meets a rigid ball or cylinder touching
// it at the origin (scenes/ball.opts, scenes/roller.opts with meshes/roller.geo). "top" the face z = 0 (contact),
// "bottom" the face z = -5 (pushed up, held by a soft spring), "sides" the four others. Refined towards the origin:
// size 0.2/L within 1.5 of it, growing by 0.3 per unit of distance beyond, at most 1.5.
If (!Exists(L))
  L = 1;
EndIf
W = 5;
H = 5;
SetNumber("ssstar/nodes", 620 * L^3 + 600 * L^2 + 850 * L); // measured: 2057, 52301, 159477 nodes at L = 1, 4, 6
SetFactory("OpenCASCADE");
Box(1) = {-W, -W, -H, 2*W, 2*W, H};
e = 1e-3;
top() = Surface In BoundingBox{-W - e, -W - e, -e, W + e, W + e, e};
bottom() = Surface In BoundingBox{-W - e, -W - e, -H - e, W + e, W + e, -H + e};
sides() = Boundary{ Volume{1}; };
sides() -= top();
sides() -= bottom();
Physical Volume("block") = {1};
Physical Surface("top") = {top()};
Physical Surface("bottom") = {bottom()};
Physical Surface("sides") = {sides()};
Field[1] = MathEval;
Field[1].F = Sprintf("Min(1.5, %g + 0.3 * Max(0, Sqrt(x*x + y*y + z*z) - 1.5))", 0.2 / L);
Background Field = 1;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;
