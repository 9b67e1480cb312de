// A slab 4 x 1 x 0.5 for objects dragged along it (scenes/drag.opts, scenes/punch.opts): x in (0, 4), y in (-0.5, 0.5),
// z in (-0.5, 0), "top" its face z = 0, "bottom" its face z = -0.5, "end" its face x = 4. Structured tetrahedra,
// finer near the top: (40L+1) x (10L+1) nodes per layer, 3L layers in the upper 0.15 and 2L below.
If (!Exists(L))
  L = 1;
EndIf
SetNumber("ssstar/nodes", (40*L+1)*(10*L+1)*(5*L+1));
SetFactory("Built-in");
Point(1) = {0, -0.5, -0.5}; Point(2) = {4, -0.5, -0.5}; Point(3) = {4, 0.5, -0.5}; Point(4) = {0, 0.5, -0.5};
Point(5) = {0, -0.5, -0.15}; Point(6) = {4, -0.5, -0.15}; Point(7) = {4, 0.5, -0.15}; Point(8) = {0, 0.5, -0.15};
Point(9) = {0, -0.5, 0};    Point(10) = {4, -0.5, 0};   Point(11) = {4, 0.5, 0};   Point(12) = {0, 0.5, 0};
// the lower layer (z from -0.5 to -0.15) and the upper one (z from -0.15 to 0)
Line(1) = {1, 2};  Line(2) = {2, 3};  Line(3) = {3, 4};  Line(4) = {4, 1};
Line(5) = {5, 6};  Line(6) = {6, 7};  Line(7) = {7, 8};  Line(8) = {8, 5};
Line(9) = {9, 10}; Line(10) = {10, 11}; Line(11) = {11, 12}; Line(12) = {12, 9};
Line(13) = {1, 5}; Line(14) = {2, 6}; Line(15) = {3, 7}; Line(16) = {4, 8};
Line(17) = {5, 9}; Line(18) = {6, 10}; Line(19) = {7, 11}; Line(20) = {8, 12};
Curve Loop(1) = {1, 2, 3, 4};       Plane Surface(1) = {1};   // bottom
Curve Loop(2) = {5, 6, 7, 8};       Plane Surface(2) = {2};   // between the layers
Curve Loop(3) = {9, 10, 11, 12};    Plane Surface(3) = {3};   // top
Curve Loop(4) = {1, 14, -5, -13};   Plane Surface(4) = {4};   // y = -0.5, lower
Curve Loop(5) = {2, 15, -6, -14};   Plane Surface(5) = {5};   // x = 4, lower
Curve Loop(6) = {3, 16, -7, -15};   Plane Surface(6) = {6};   // y = 0.5, lower
Curve Loop(7) = {4, 13, -8, -16};   Plane Surface(7) = {7};   // x = 0, lower
Curve Loop(8) = {5, 18, -9, -17};   Plane Surface(8) = {8};   // y = -0.5, upper
Curve Loop(9) = {6, 19, -10, -18};  Plane Surface(9) = {9};   // x = 4, upper
Curve Loop(10) = {7, 20, -11, -19}; Plane Surface(10) = {10}; // y = 0.5, upper
Curve Loop(11) = {8, 17, -12, -20}; Plane Surface(11) = {11}; // x = 0, upper
Surface Loop(1) = {1, 2, 4, 5, 6, 7};   Volume(1) = {1};
Surface Loop(2) = {2, 3, 8, 9, 10, 11}; Volume(2) = {2};
Transfinite Curve {1, 3, 5, 7, 9, 11} = 40*L + 1;
Transfinite Curve {2, 4, 6, 8, 10, 12} = 10*L + 1;
Transfinite Curve {13, 14, 15, 16} = 2*L + 1;
Transfinite Curve {17, 18, 19, 20} = 3*L + 1;
Transfinite Surface {1:11};
Transfinite Volume {1, 2};
Physical Surface("bottom") = {1};
Physical Surface("top") = {3};
Physical Surface("end") = {5, 9};
Physical Volume("slab") = {1, 2};
