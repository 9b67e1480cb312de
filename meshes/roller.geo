// A block 20 x Ly x 10 (x in (-10, 10), y in (-Ly/2, Ly/2) with Ly = 12, z in (-10, 0)) long along y, whose top face
// z = 0 meets a rigid cylinder along y touching it on the line x = z = 0 (scenes/roller.opts). "top" the face z = 0
// (contact), "bottom" the face z = -10 (pushed up, held by a soft spring), "sides" the four others. The cross-section
// x-z is meshed in 2D, refined towards the line of contact (size 0.2/L within 1.5 of it, growing by 0.3 per unit of
// distance beyond, at most 3), and extruded along y in 12 L layers of tetrahedra: every section y = const of nodes
// is the same, so that the force per unit length at y = 0 is the sum of the reactions of the nodes there divided by
// the layer thickness.
If (!Exists(L))
  L = 1;
EndIf
W = 10;
H = 10;
Ly = 12;
SetNumber("ssstar/nodes", 900 * L^3);
SetFactory("Built-in");
Point(1) = {-W, -Ly/2, -H};  Point(2) = {W, -Ly/2, -H};  Point(3) = {W, -Ly/2, 0};  Point(4) = {0, -Ly/2, 0};
Point(5) = {-W, -Ly/2, 0};
Line(1) = {1, 2};  Line(2) = {2, 3};  Line(3) = {3, 4};  Line(4) = {4, 5};  Line(5) = {5, 1};
Curve Loop(1) = {1, 2, 3, 4, 5};
Plane Surface(1) = {1};
Field[1] = MathEval;
Field[1].F = Sprintf("Min(3, %g + 0.3 * Max(0, Sqrt(x*x + z*z) - 1.5))", 0.2 / L);
Background Field = 1;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;
out[] = Extrude {0, Ly, 0} { Surface{1}; Layers{12 * L}; };
// out[0] the far end, out[1] the volume, out[2..6] the faces swept by lines 1..5
Physical Volume("block") = {out[1]};
Physical Surface("top") = {out[4], out[5]};
Physical Surface("bottom") = {out[2]};
Physical Surface("sides") = {1, out[0], out[3], out[6]};
