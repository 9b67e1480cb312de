// A cantilever beam 10 x 1 x 1 (docs/guide/displacements-and-stresses.md): x in (0, 10) along its axis, y and z in
// (-0.5, 0.5), "root" its face x = 0 (clamped), "tip" its face x = 10 (loaded). Structured tetrahedra,
// (20L+1) x (2L+1) x (2L+1) nodes.
If (!Exists(L))
  L = 2;
EndIf
SetNumber("ssstar/nodes", (20*L+1)*(2*L+1)*(2*L+1));
SetFactory("Built-in");
Point(1) = {0, -0.5, -0.5};  Point(2) = {10, -0.5, -0.5};  Point(3) = {10, 0.5, -0.5};  Point(4) = {0, 0.5, -0.5};
Point(5) = {0, -0.5, 0.5};   Point(6) = {10, -0.5, 0.5};   Point(7) = {10, 0.5, 0.5};   Point(8) = {0, 0.5, 0.5};
Line(1) = {1, 2};  Line(2) = {2, 3};  Line(3) = {3, 4};  Line(4) = {4, 1};
Line(5) = {5, 6};  Line(6) = {6, 7};  Line(7) = {7, 8};  Line(8) = {8, 5};
Line(9) = {1, 5};  Line(10) = {2, 6}; Line(11) = {3, 7}; Line(12) = {4, 8};
Curve Loop(1) = {1, 2, 3, 4};      Plane Surface(1) = {1};   // z = -0.5
Curve Loop(2) = {5, 6, 7, 8};      Plane Surface(2) = {2};   // z = 0.5
Curve Loop(3) = {9, -8, -12, 4};   Plane Surface(3) = {3};   // x = 0: root
Curve Loop(4) = {2, 11, -6, -10};  Plane Surface(4) = {4};   // x = 10: tip
Curve Loop(5) = {1, 10, -5, -9};   Plane Surface(5) = {5};   // y = -0.5
Curve Loop(6) = {3, 12, -7, -11};  Plane Surface(6) = {6};   // y = 0.5
Surface Loop(1) = {1, 2, 3, 4, 5, 6};
Volume(1) = {1};
Transfinite Curve {1, 3, 5, 7} = 20*L + 1;
Transfinite Curve {2, 4, 6, 8, 9, 10, 11, 12} = 2*L + 1;
Transfinite Surface {1, 2, 3, 4, 5, 6};
Transfinite Volume {1};
Physical Surface("root") = {3};
Physical Surface("tip") = {4};
Physical Volume("beam") = {1};
