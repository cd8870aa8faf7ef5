// A w x h block with its lower left corner at (x0, y0), meshed by a
// structured grid of n x m quadrilaterals (symmetric about x = x0 + w/2).
// Physical curves bottom, right, top, left; physical points tip (the top's
// middle), feet (the two bottom corners) and corners (the two top corners).
DefineConstant[ x0 = 0, y0 = 1, w = 1, h = 0.5, n = 8, m = 4 ];
Point(1) = {x0, y0, 0};
Point(2) = {x0 + w, y0, 0};
Point(3) = {x0 + w, y0 + h, 0};
Point(4) = {x0 + w / 2, y0 + h, 0};
Point(5) = {x0, y0 + h, 0};
Point(6) = {x0 + w / 2, y0, 0};
Line(1) = {1, 6}; Line(2) = {6, 2}; Line(3) = {2, 3}; Line(4) = {3, 4}; Line(5) = {4, 5}; Line(6) = {5, 1};
Line(7) = {6, 4};
Curve Loop(1) = {1, 7, 5, 6}; Plane Surface(1) = {1};
Curve Loop(2) = {2, 3, 4, -7}; Plane Surface(2) = {2};
Transfinite Curve{1, 2, 4, 5} = n / 2 + 1;
Transfinite Curve{3, 6, 7} = m + 1;
Transfinite Surface{1} = {1, 6, 4, 5};
Transfinite Surface{2} = {6, 2, 3, 4};
Recombine Surface{1, 2};
Physical Curve("bottom") = {1, 2};
Physical Curve("right") = {3};
Physical Curve("top") = {4, 5};
Physical Curve("left") = {6};
Physical Point("tip") = {4};
Physical Point("feet") = {1, 2};
Physical Point("corners") = {3, 5};
Physical Surface("block") = {1, 2};
