// a disk of radius R centred at the origin, n nodes on its rim (n/4 per quarter),
// size h inside; the rim named as a whole and by parts
DefineConstant[ R = 0.05, n = 256, h = 0.005 ];
Point(1) = {0, 0, 0, h};
Point(2) = {R, 0, 0, h}; Point(3) = {0, R, 0, h}; Point(4) = {-R, 0, 0, h}; Point(5) = {0, -R, 0, h};
Circle(1) = {2, 1, 3}; Circle(2) = {3, 1, 4}; Circle(3) = {4, 1, 5}; Circle(4) = {5, 1, 2};
Transfinite Curve{1:4} = n/4 + 1;
Curve Loop(1) = {1:4};
Plane Surface(1) = {1};
Point{1} In Surface{1};
Physical Surface("disk") = {1};
Physical Curve("rim") = {1:4};
Physical Curve("lower") = {3, 4};
Physical Curve("sw") = {3};
Physical Curve("se") = {4};
Physical Point("centre") = {1};
