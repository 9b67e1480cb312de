// A flat block on a long one, not fused (scenes/track.opts): "base" 3 x 1 x 0.25 on z = 0 (x in (0, 3)), "slider"
// 0.5 x 0.5 x 0.1 on it at x in (0.25, 0.75), y in (0.25, 0.75), meshed apart with different sizes (h = 0.1/L below,
// 0.05/L above): the slider's face "slider_bottom" lies on the base's face "base_top" without matching its mesh, and
// can slide along it by more than four of its lengths. "bottom": the base's face z = 0; "slider_top": the slider's
// face z = 0.35 (flat, so that a push on it tilts the slider little: the whole face stays in contact).
If (!Exists(L))
  L = 1;
EndIf
SetNumber("ssstar/nodes", (30 * L + 1) * (10 * L + 1) * (3 * L + 1) * 1.3 + (10 * L + 1)^2 * (2 * L + 1) * 1.3);
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 3, 1, 0.25};
Box(2) = {0.25, 0.25, 0.25, 0.5, 0.5, 0.1};
MeshSize{ PointsOf{ Volume{1}; } } = 0.1 / L;
MeshSize{ PointsOf{ Volume{2}; } } = 0.05 / L;
b1[] = Abs(Boundary{ Volume{1}; }); // OpenCASCADE's box faces: x = min, max, y = min, max, z = min, max
b2[] = Abs(Boundary{ Volume{2}; });
Physical Volume("base") = {1};
Physical Volume("slider") = {2};
Physical Surface("bottom") = {b1[4]};
Physical Surface("base_top") = {b1[5]};
Physical Surface("slider_bottom") = {b2[4]};
Physical Surface("slider_top") = {b2[5]};
