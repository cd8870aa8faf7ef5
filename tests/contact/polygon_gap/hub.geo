// ring a <= r <= c (the hub), n nodes on its bore
DefineConstant[ a = 1.0, c = 2.0, n = 64, h = 0.1 ];
Point(1) = {0, 0, 0, h};
Point(2) = {a, 0, 0, h}; Point(3) = {0, a, 0, h}; Point(4) = {-a, 0, 0, h}; Point(5) = {0, -a, 0, h};
Point(6) = {c, 0, 0, h}; Point(7) = {0, c, 0, h}; Point(8) = {-c, 0, 0, h}; Point(9) = {0, -c, 0, h};
Circle(1) = {2, 1, 3}; Circle(2) = {3, 1, 4}; Circle(3) = {4, 1, 5}; Circle(4) = {5, 1, 2};
Circle(5) = {6, 1, 7}; Circle(6) = {7, 1, 8}; Circle(7) = {8, 1, 9}; Circle(8) = {9, 1, 6};
Transfinite Curve{1:4} = n/4 + 1;
Curve Loop(1) = {5:8}; Curve Loop(2) = {1:4};
Plane Surface(1) = {1, 2};
Physical Surface("hub") = {1};
Physical Curve("bore") = {1:4};
Physical Curve("outer") = {5:8};
Physical Point("east") = {6};
Physical Point("north") = {7};
