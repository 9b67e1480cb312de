// A rigid ball given by its surface (-obstacle_<G> mesh:FILE.msh; bench/search.py): the sphere of radius 10 centred
// at (0, 0, 10), touching the plane z = 0 at the origin as scenes/ball.opts's sphere:0,0,10,10 does, its triangles
// oriented outwards (OpenCASCADE). Uniform size 0.45/L: about 15 000 triangles at L = 1, 60 000 at L = 2.
//   gmsh -2 -setnumber L 2 -format msh41 meshes/ball_surface.geo -o ball_surface_L2.msh
If (!Exists(L))
  L = 1;
EndIf
SetFactory("OpenCASCADE");
Sphere(1) = {0, 0, 10, 10};
Mesh.MeshSizeMin = 0.45 / L;
Mesh.MeshSizeMax = 0.45 / L;
Physical Surface("ball") = {Boundary{ Volume{1}; }};
