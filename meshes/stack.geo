// Two blocks stacked, not fused (scenes/patch.opts, the contact patch test): "base" 1 x 1 x 0.5 on z = 0 and "lid"
// 1 x 1 x 0.5 on top of it, meshed apart with different sizes (h = 0.25/L below, 0.35/L above), so that their
// meshes do not match at the interface z = 0.5: the base's face "base_top" and the lid's face "lid_bottom" are two
// surfaces at the same place. "bottom": the base's face z = 0; "top": the lid's face z = 1.
If (!Exists(L))
  L = 1;
EndIf
SetNumber("ssstar/nodes", 2 * (5.6 * L + 1)^3);
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 1, 1, 0.5};
Box(2) = {0, 0, 0.5, 1, 1, 0.5};
e = 1e-6;
MeshSize{ PointsOf{ Volume{1}; } } = 0.25 / L;
MeshSize{ PointsOf{ Volume{2}; } } = 0.35 / L;
Physical Volume("base") = {1};
Physical Volume("lid") = {2};
Physical Surface("bottom") = Surface In BoundingBox{-e, -e, -e, 1 + e, 1 + e, e};
b1[] = Abs(Boundary{ Volume{1}; }); // OpenCASCADE's box faces: x = min, max, y = min, max, z = min, max
b2[] = Abs(Boundary{ Volume{2}; });
Physical Surface("base_top") = {b1[5]};
Physical Surface("lid_bottom") = {b2[4]};
Physical Surface("top") = Surface In BoundingBox{-e, -e, 1 - e, 1 + e, 1 + e, 1 + e};
