// Upper half of a hollow shaft r_i <= r <= r_o, y >= 0, centred at the
// origin, a structured quad mesh symmetric about x = 0 (n elements along
// each quarter arc, m through the thickness), fixed on its two flat ends.
DefineConstant[ ri = 0.6, ro = 1.0, n = 17, m = 4 ];
Point(1) = {0, 0, 0};
Point(2) = { ri, 0, 0};
Point(3) = { ro, 0, 0};
Point(4) = {0, ro, 0};
Point(5) = {-ro, 0, 0};
Point(6) = {-ri, 0, 0};
Point(7) = {0, ri, 0};
Line(1) = {2, 3};
Circle(2) = {3, 1, 4};
Circle(3) = {4, 1, 5};
Line(4) = {5, 6};
Circle(5) = {6, 1, 7};
Circle(6) = {7, 1, 2};
Line(7) = {7, 4};
Curve Loop(1) = {1, 2, -7, 6};
Plane Surface(1) = {1};
Curve Loop(2) = {7, 3, 4, 5};
Plane Surface(2) = {2};
Transfinite Curve{2, 3, 5, 6} = n + 1;
Transfinite Curve{1, 4, 7} = m + 1;
Transfinite Surface{1} = {2, 3, 4, 7};
Transfinite Surface{2} = {7, 4, 5, 6};
Recombine Surface{1, 2};
Physical Curve("bottom") = {1, 4};
Physical Curve("arc") = {2, 3};
Physical Curve("hole") = {5, 6};
Physical Surface("tube") = {1, 2};
