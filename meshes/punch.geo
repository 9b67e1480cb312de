// A rigid flat punch for -obstacle_<G> mesh:meshes/punch.msh (scenes/punch.opts): the box 0.4 x 0.4 x 0.2 standing on
// the plane z = 0 with its face z = 0 centred at the origin, bounded by 12 triangles oriented out of it (OpenCASCADE).
// Regenerate: gmsh -2 -format msh22 meshes/punch.geo -o meshes/punch.msh
SetFactory("OpenCASCADE");
Box(1) = {-0.2, -0.2, 0, 0.4, 0.4, 0.2};
Mesh.MeshSizeMin = 1;
Mesh.MeshSizeMax = 1;
Physical Surface("punch") = {Boundary{Volume{1};}};
