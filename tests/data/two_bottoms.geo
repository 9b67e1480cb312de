// A block 1 x 1 x 0.5 on the plane z = 0 whose bottom face is two contact groups: "left" (x < 0.5) and "right"
// (x > 0.5); "top" its face z = 0.5 (tests/suite_outcomes.py: a group without -friction_<G> takes the solver's
// coefficient). Structured tetrahedra, (4L+1) x (4L+1) x (2L+1) nodes.
If (!Exists(L))
  L = 2;
EndIf
SetNumber("ssstar/nodes", (4*L+1)*(4*L+1)*(2*L+1));
SetFactory("Built-in");
Point(1) = {0, 0, 0};    Point(2) = {0.5, 0, 0};    Point(3) = {1, 0, 0};
Point(4) = {0, 1, 0};    Point(5) = {0.5, 1, 0};    Point(6) = {1, 1, 0};
Point(7) = {0, 0, 0.5};  Point(8) = {0.5, 0, 0.5};  Point(9) = {1, 0, 0.5};
Point(10) = {0, 1, 0.5}; Point(11) = {0.5, 1, 0.5}; Point(12) = {1, 1, 0.5};
// bottom z = 0
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {4, 5}; Line(4) = {5, 6};
Line(5) = {1, 4}; Line(6) = {2, 5}; Line(7) = {3, 6};
// top z = 0.5
Line(8) = {7, 8}; Line(9) = {8, 9}; Line(10) = {10, 11}; Line(11) = {11, 12};
Line(12) = {7, 10}; Line(13) = {8, 11}; Line(14) = {9, 12};
// vertical
Line(15) = {1, 7}; Line(16) = {2, 8}; Line(17) = {3, 9}; Line(18) = {4, 10}; Line(19) = {5, 11}; Line(20) = {6, 12};
Curve Loop(1) = {1, 6, -3, -5};     Plane Surface(1) = {1};   // bottom, left half
Curve Loop(2) = {2, 7, -4, -6};     Plane Surface(2) = {2};   // bottom, right half
Curve Loop(3) = {8, 13, -10, -12};  Plane Surface(3) = {3};   // top, left half
Curve Loop(4) = {9, 14, -11, -13};  Plane Surface(4) = {4};   // top, right half
Curve Loop(5) = {1, 16, -8, -15};   Plane Surface(5) = {5};   // y = 0
Curve Loop(6) = {2, 17, -9, -16};   Plane Surface(6) = {6};
Curve Loop(7) = {3, 19, -10, -18};  Plane Surface(7) = {7};   // y = 1
Curve Loop(8) = {4, 20, -11, -19};  Plane Surface(8) = {8};
Curve Loop(9) = {5, 18, -12, -15};  Plane Surface(9) = {9};   // x = 0
Curve Loop(10) = {7, 20, -14, -17}; Plane Surface(10) = {10}; // x = 1
Curve Loop(11) = {6, 19, -13, -16}; Plane Surface(11) = {11}; // x = 0.5, inside
Surface Loop(1) = {1, 3, 5, 7, 9, 11};   Volume(1) = {1};
Surface Loop(2) = {2, 4, 6, 8, 10, 11};  Volume(2) = {2};
Transfinite Curve {1, 2, 3, 4, 8, 9, 10, 11} = 2*L + 1;
Transfinite Curve {5, 6, 7, 12, 13, 14} = 4*L + 1;
Transfinite Curve {15, 16, 17, 18, 19, 20} = 2*L + 1;
Transfinite Surface {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11};
Transfinite Volume {1, 2};
Physical Surface("left") = {1};
Physical Surface("right") = {2};
Physical Surface("top") = {3, 4};
Physical Volume("block") = {1, 2};
