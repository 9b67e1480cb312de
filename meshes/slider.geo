// A small block on a large one, not fused (scenes/slider.opts): "base" 1 x 1 x 0.5 on z = 0, "slider"
// 0.5 x 0.5 x 0.25 on its middle, meshed apart with different sizes (h = 0.2/L below, 0.11/L above): the slider's face
// "slider_bottom" lies on the base's face "base_top" without matching its mesh. "bottom": the base's face z = 0;
// "slider_top": the slider's face z = 0.75.
If (!Exists(L))
  L = 1;
EndIf
SetNumber("ssstar/nodes", (5 * L + 1)^3 / 2 + (4.5 * L + 1)^3 / 4);
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 1, 1, 0.5};
Box(2) = {0.25, 0.25, 0.5, 0.5, 0.5, 0.25};
MeshSize{ PointsOf{ Volume{1}; } } = 0.2 / L;
MeshSize{ PointsOf{ Volume{2}; } } = 0.11 / L;
b1[] = Abs(Boundary{ Volume{1}; }); // OpenCASCADE's box faces: x = min, max, y = min, max, z = min, max
b2[] = Abs(Boundary{ Volume{2}; });
Physical Volume("base") = {1};
Physical Volume("slider") = {2};
Physical Surface("bottom") = {b1[4]};
Physical Surface("base_top") = {b1[5]};
Physical Surface("slider_bottom") = {b2[4]};
Physical Surface("slider_top") = {b2[5]};
