// quarter of the hub: a <= r <= c, 0 <= theta <= 90 degrees
DefineConstant[ a = 1.0, c = 2.0, n = 32, h = 0.05 ];
Point(1) = {0, 0, 0, h};
Point(2) = {a, 0, 0, h}; Point(3) = {c, 0, 0, h}; Point(4) = {0, c, 0, h}; Point(5) = {0, a, 0, h};
Line(1) = {2, 3}; Circle(2) = {3, 1, 4}; Line(3) = {4, 5}; Circle(4) = {5, 1, 2};
Transfinite Curve{4} = n + 1;
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Physical Surface("hub") = {1};
Physical Curve("bore") = {4};
Physical Curve("xaxis") = {1};
Physical Curve("yaxis") = {3};
