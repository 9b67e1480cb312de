// The unit cube [0, 1]^3 with its six faces named (docs/guide/large-deformation.md, tests/suite_hyperelastic.py):
// "bottom" z = 0, "top" z = 1, "left" x = 0, "right" x = 1, "front" y = 0, "back" y = 1; the volume "cube".
// Unstructured tetrahedra of size 0.5/L.
If (!Exists(L))
  L = 1;
EndIf
SetNumber("ssstar/nodes", 20 * L^3);
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 1, 1, 1};
Physical Surface("bottom") = {Surface In BoundingBox{-0.1, -0.1, -0.1, 1.1, 1.1, 0.1}};
Physical Surface("top") = {Surface In BoundingBox{-0.1, -0.1, 0.9, 1.1, 1.1, 1.1}};
Physical Surface("left") = {Surface In BoundingBox{-0.1, -0.1, -0.1, 0.1, 1.1, 1.1}};
Physical Surface("right") = {Surface In BoundingBox{0.9, -0.1, -0.1, 1.1, 1.1, 1.1}};
Physical Surface("front") = {Surface In BoundingBox{-0.1, -0.1, -0.1, 1.1, 0.1, 1.1}};
Physical Surface("back") = {Surface In BoundingBox{-0.1, 0.9, -0.1, 1.1, 1.1, 1.1}};
Physical Volume("cube") = {1};
Mesh.MeshSizeMin = 0.5 / L;
Mesh.MeshSizeMax = 0.5 / L;
