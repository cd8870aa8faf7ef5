// Square [0, L] x [0, L] for the deck_reader tests; L and hc can be set from
// the deck (MESH gmsh file=deck_square.geo L=2 hc=0.5 -> gmsh -setnumber ...).
DefineConstant[ L = {1, Name "L"}, hc = {0.25, Name "hc"} ];
Point(1) = {0, 0, 0, hc};
Point(2) = {L, 0, 0, hc};
Point(3) = {L, L, 0, hc};
Point(4) = {0, L, 0, hc};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Physical Curve("bottom") = {1};
Physical Curve("right") = {2};
Physical Curve("top") = {3};
Physical Curve("left") = {4};
Physical Surface("square") = {1};
