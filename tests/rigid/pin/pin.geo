// solid disk of radius r (the pin), n nodes on its rim; the centre and the
// point (r/2, 0) are mesh nodes (physical points centre, east)
DefineConstant[ r = 1.0, n = 256, h = 0.05 ];
Point(1) = {0, 0, 0, h}; Point(2) = {r, 0, 0, h}; Point(3) = {0, r, 0, h};
Point(4) = {-r, 0, 0, h}; Point(5) = {0, -r, 0, h}; Point(6) = {r / 2, 0, 0, h};
Circle(1) = {2, 1, 3}; Circle(2) = {3, 1, 4}; Circle(3) = {4, 1, 5}; Circle(4) = {5, 1, 2};
Transfinite Curve{1:4} = n / 4 + 1;
Curve Loop(1) = {1:4};
Plane Surface(1) = {1};
Point{1, 6} In Surface{1};
Physical Surface("pin") = {1};
Physical Curve("rim") = {1:4};
Physical Point("centre") = {1};
Physical Point("east") = {6};
