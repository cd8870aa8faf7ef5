// Upper half-ring r_i <= r <= r_o, y >= 0, centred at the origin (the body
// held only by contact), element size h (ho on the outer arc).
DefineConstant[ ri = 1.0, ro = 1.5, h = 0.1, ho = 0.1 ];
Point(1) = {0, 0, 0, h};
Point(2) = { ri, 0, 0, h};
Point(3) = { ro, 0, 0, ho};
Point(4) = {-ro, 0, 0, ho};
Point(5) = {-ri, 0, 0, h};
Point(6) = {0, ri, 0, h};
Point(7) = {0, ro, 0, ho};
Line(1) = {2, 3};
Circle(2) = {3, 1, 7};
Circle(3) = {7, 1, 4};
Line(4) = {4, 5};
Circle(5) = {5, 1, 6};
Circle(6) = {6, 1, 2};
Curve Loop(1) = {1, 2, 3, 4, 5, 6};
Plane Surface(1) = {1};
Physical Curve("right_end") = {1};
Physical Curve("outer") = {2, 3};
Physical Curve("left_end") = {4};
Physical Curve("inner") = {5, 6};
Physical Point("top") = {7};
Physical Surface("ring") = {1};
