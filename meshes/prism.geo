// The seed's elastic prism (0,2)x(0,1)x(0,1), structured tetrahedra.
// Level L: (4L+1) x (2L+1) x (2L+1) nodes.  gmsh -3 -setnumber L 6 prism.geo
If (!Exists(L))
  L = 3;
EndIf
// the node count of the level, read by ssstar before meshing (memory check)
SetNumber("ssstar/nodes", (4*L+1)*(2*L+1)^2);
SetFactory("Built-in");
Point(1) = {0, 0, 0};  Point(2) = {2, 0, 0};  Point(3) = {2, 1, 0};  Point(4) = {0, 1, 0};
Point(5) = {0, 0, 1};  Point(6) = {2, 0, 1};  Point(7) = {2, 1, 1};  Point(8) = {0, 1, 1};
Line(1) = {1, 2};  Line(2) = {2, 3};  Line(3) = {3, 4};  Line(4) = {4, 1};
Line(5) = {5, 6};  Line(6) = {6, 7};  Line(7) = {7, 8};  Line(8) = {8, 5};
Line(9) = {1, 5};  Line(10) = {2, 6}; Line(11) = {3, 7}; Line(12) = {4, 8};
Curve Loop(1) = {1, 2, 3, 4};      Plane Surface(1) = {1};   // z = 0
Curve Loop(2) = {5, 6, 7, 8};      Plane Surface(2) = {2};   // z = 1
Curve Loop(3) = {9, -8, -12, 4};   Plane Surface(3) = {3};   // x = 0
Curve Loop(4) = {2, 11, -6, -10};  Plane Surface(4) = {4};   // x = 2
Curve Loop(5) = {1, 10, -5, -9};   Plane Surface(5) = {5};   // y = 0
Curve Loop(6) = {3, 12, -7, -11};  Plane Surface(6) = {6};   // y = 1
Surface Loop(1) = {1, 2, 3, 4, 5, 6};
Volume(1) = {1};
Transfinite Curve {1, 3, 5, 7} = 4*L + 1;
Transfinite Curve {2, 4, 6, 8, 9, 10, 11, 12} = 2*L + 1;
Transfinite Surface {1, 2, 3, 4, 5, 6};
Transfinite Volume {1};
Physical Surface("contact") = {1};
Physical Surface("top") = {2};
Physical Surface("dirichlet") = {3};
Physical Surface("right") = {4};
Physical Volume("body") = {1};
