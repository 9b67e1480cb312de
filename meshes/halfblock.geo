// Half of the block of block.geo cut at x = 0 (docs/guide/displacements-and-stresses.md, tests/suite_displacement.py):
// x in (0, 0.5), y in (-0.5, 0.5), z in (0, 0.5); "bottom" its face z = 0, "top" its face z = 0.5, "sym" its face
// x = 0 (a plane of symmetry). Structured tetrahedra, (2L+1) x (4L+1) x (2L+1) nodes.
If (!Exists(L))
  L = 1;
EndIf
SetNumber("ssstar/nodes", (2*L+1)*(4*L+1)*(2*L+1));
SetFactory("Built-in");
Point(1) = {0, -0.5, 0};    Point(2) = {0.5, -0.5, 0};    Point(3) = {0.5, 0.5, 0};    Point(4) = {0, 0.5, 0};
Point(5) = {0, -0.5, 0.5};  Point(6) = {0.5, -0.5, 0.5};  Point(7) = {0.5, 0.5, 0.5};  Point(8) = {0, 0.5, 0.5};
Line(1) = {1, 2};  Line(2) = {2, 3};  Line(3) = {3, 4};  Line(4) = {4, 1};
Line(5) = {5, 6};  Line(6) = {6, 7};  Line(7) = {7, 8};  Line(8) = {8, 5};
Line(9) = {1, 5};  Line(10) = {2, 6}; Line(11) = {3, 7}; Line(12) = {4, 8};
Curve Loop(1) = {1, 2, 3, 4};      Plane Surface(1) = {1};   // bottom
Curve Loop(2) = {5, 6, 7, 8};      Plane Surface(2) = {2};   // top
Curve Loop(3) = {9, -8, -12, 4};   Plane Surface(3) = {3};   // x = 0: sym
Curve Loop(4) = {2, 11, -6, -10};  Plane Surface(4) = {4};   // x = 0.5
Curve Loop(5) = {1, 10, -5, -9};   Plane Surface(5) = {5};
Curve Loop(6) = {3, 12, -7, -11};  Plane Surface(6) = {6};
Surface Loop(1) = {1, 2, 3, 4, 5, 6};
Volume(1) = {1};
Transfinite Curve {1, 3, 5, 7} = 2*L + 1;
Transfinite Curve {2, 4, 6, 8} = 4*L + 1;
Transfinite Curve {9, 10, 11, 12} = 2*L + 1;
Transfinite Surface {1, 2, 3, 4, 5, 6};
Transfinite Volume {1};
Physical Surface("bottom") = {1};
Physical Surface("top") = {2};
Physical Surface("sym") = {3};
Physical Volume("block") = {1};
