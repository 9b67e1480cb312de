// An unstructured slab 4.2 x 4.2 x 0.28 (scenes/press.opts; the slab of issue 31): x, y in (-2.1, 2.1), z in (0, 0.28),
// "bottom" its whole face z = 0 (the contact group), "patch" the square 0.5 x 0.5 in the middle of its top face (the
// press), "top" the rest of the top face, "sides" its four faces x, y = +-2.1. gmsh's unstructured tetrahedra of size
// 0.1/L: 6 619 nodes, 2 149 of them on the bottom at L = 1 (the contact nodes: a third of the nodes, most of them
// separated under a central press); 6.3 L^3 thousand nodes.
If (!Exists(L))
  L = 1;
EndIf
SetNumber("ssstar/nodes", 6600 * L^3);
SetFactory("OpenCASCADE");
W = 4.2;
T = 0.28;
P = 0.5;
Box(1) = {-W/2, -W/2, 0, W, W, T};
Rectangle(10) = {-P/2, -P/2, T, P, P};
v() = BooleanFragments{ Volume{1}; Delete; }{ Surface{10}; Delete; };
Mesh.CharacteristicLengthMax = 0.1 / L;
Mesh.CharacteristicLengthMin = 0.1 / L;
bottom() = Surface In BoundingBox{-W, -W, -0.01, W, W, 0.01};
top() = Surface In BoundingBox{-W, -W, T - 0.01, W, W, T + 0.01};
patch() = Surface In BoundingBox{-P/2 - 0.01, -P/2 - 0.01, T - 0.01, P/2 + 0.01, P/2 + 0.01, T + 0.01};
top() -= patch();
sides() = Boundary{ Volume{1}; };
sides() -= bottom();
sides() -= top();
sides() -= patch();
Physical Surface("bottom") = {bottom()};
Physical Surface("patch") = {patch()};
Physical Surface("top") = {top()};
Physical Surface("sides") = {sides()};
Physical Volume("slab") = {1};
