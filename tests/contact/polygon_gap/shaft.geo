// solid disk of radius r (the shaft), n nodes on its rim
DefineConstant[ r = 1.001, n = 64, h = 0.1 ];
Point(1) = {0, 0, 0, h};
Point(2) = {r, 0, 0, h}; Point(3) = {0, r, 0, h}; Point(4) = {-r, 0, 0, h}; Point(5) = {0, -r, 0, h};
Circle(1) = {2, 1, 3}; Circle(2) = {3, 1, 4}; Circle(3) = {4, 1, 5}; Circle(4) = {5, 1, 2};
Transfinite Curve{1:4} = n/4 + 1;
Curve Loop(1) = {1:4};
Plane Surface(1) = {1};
Point{1} In Surface{1};
Physical Surface("shaft") = {1};
Physical Curve("rim") = {1:4};
Physical Point("centre") = {1};
Physical Point("east") = {2};
