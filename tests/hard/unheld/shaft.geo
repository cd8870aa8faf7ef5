// Upper half-disk x^2 + y^2 <= r^2, y >= 0 (the shaft, fixed on its flat
// bottom), element size h.
DefineConstant[ r = 1.0, h = 0.1 ];
Point(1) = {0, 0, 0, h};
Point(2) = { r, 0, 0, h};
Point(3) = {0, r, 0, h};
Point(4) = {-r, 0, 0, h};
Circle(1) = {2, 1, 3};
Circle(2) = {3, 1, 4};
Line(3) = {4, 2};
Curve Loop(1) = {1, 2, 3};
Plane Surface(1) = {1};
Physical Curve("arc") = {1, 2};
Physical Curve("bottom") = {3};
Physical Surface("shaft") = {1};
