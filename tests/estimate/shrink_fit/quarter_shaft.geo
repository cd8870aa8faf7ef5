// quarter of the shaft: the sector 0 <= theta <= 90 degrees of a disk of radius r
DefineConstant[ r = 1.001, n = 32, h = 0.05 ];
Point(1) = {0, 0, 0, h}; Point(2) = {r, 0, 0, h}; Point(3) = {0, r, 0, h};
Line(1) = {1, 2}; Circle(2) = {2, 1, 3}; Line(3) = {3, 1};
Transfinite Curve{2} = n + 1;
Curve Loop(1) = {1, 2, 3};
Plane Surface(1) = {1};
Physical Surface("shaft") = {1};
Physical Curve("rim") = {2};
Physical Curve("xaxis") = {1};
Physical Curve("yaxis") = {3};
