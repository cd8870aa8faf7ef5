// the skate: a W x H block, nx x ny quadrangles (transfinite), its sides named,
// and the middle nodes of its left and right sides as physical points
DefineConstant[ W = 100, H = 50, nx = 8, ny = 4 ];
Point(1) = {0, 0, 0};  Point(2) = {W, 0, 0};  Point(3) = {W, H, 0};  Point(4) = {0, H, 0};
Point(5) = {W, H/2, 0};  Point(6) = {0, H/2, 0};
Line(1) = {1, 2}; Line(2) = {2, 5}; Line(3) = {5, 3}; Line(4) = {3, 4}; Line(5) = {4, 6}; Line(6) = {6, 1};
Transfinite Curve{1, 4} = nx + 1;
Transfinite Curve{2, 3, 5, 6} = ny/2 + 1;
Curve Loop(1) = {1, 2, 3, 4, 5, 6};
Plane Surface(1) = {1};
Transfinite Surface{1} = {1, 2, 3, 4};
Recombine Surface{1};
Physical Surface("skate") = {1};
Physical Curve("bottom") = {1};
Physical Curve("right") = {2, 3};
Physical Curve("top") = {4};
Physical Curve("left") = {5, 6};
Physical Point("pright") = {5};
Physical Point("pleft") = {6};
