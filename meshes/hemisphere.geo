// A half ball for large indentation (scenes/hemisphere.opts, bench/getfem_ball.py): the lower hemisphere of the ball
// of radius R = 10 centred at (0, 0, R), its pole at the origin touching the plane z = 0, its flat face "top" at
// z = R. The whole spherical surface is the group "sphere" (an indentation of 0.3 R flattens a contact zone of radius
// about 0.6 R and bulges the side into the plane: no cap of hertz.geo's size covers it). The mesh has the size 1/L
// within 8 of the pole (the contact zone), growing by 0.25 per unit of distance beyond, at most 2.5/L.
If (!Exists(L))
  L = 1;
EndIf
R = 10;
SetNumber("ssstar/nodes", 1100 * L^3);   // measured: 1212, 8112 nodes for L = 1, 2
SetFactory("OpenCASCADE");
Sphere(1) = {0, 0, R, R, -Pi/2, 0, 2*Pi};
top() = Surface In BoundingBox{-R - 0.1, -R - 0.1, R - 0.1, R + 0.1, R + 0.1, R + 0.1};
all() = Boundary{ Volume{1}; };
all() -= top();
Physical Volume("ball") = {1};
Physical Surface("sphere") = {all()};
Physical Surface("top") = {top()};
Field[1] = MathEval;
Field[1].F = Sprintf("Min(%g, (1 + 0.25 * Max(0, Sqrt(x*x + y*y + z*z) - 8)) / %g)", 2.5 / L, L);
Background Field = 1;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;
