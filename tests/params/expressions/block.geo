// A w x 1 block meshed by gmsh: the lower body of the batch decks.
DefineConstant[ h = 0.25, w = 1 ];
Point(1) = {0, 0, 0, h}; Point(2) = {w, 0, 0, h}; Point(3) = {w, 1, 0, h}; Point(4) = {0, 1, 0, h};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
Physical Curve("bottom") = {1}; Physical Curve("top") = {3};
Physical Surface("block") = {1};
