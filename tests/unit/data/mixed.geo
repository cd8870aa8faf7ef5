// Rectangle [0,2]x[0,1] in two unit squares, n nodes per side (n = 4):
// left square recombined into (n-1)^2 quadrangles, right square 2 (n-1)^2
// triangles; 2 n^2 - n nodes.  Physical surfaces "quads" (left) and "whole"
// (both); physical curves "bottom" (both bottoms) and "right" (x = 2); physical
// point "right" at (2,0) shares the name of the curve.
n = 4;
Point(1) = {0, 0, 0, 1};
Point(2) = {1, 0, 0, 1};
Point(3) = {2, 0, 0, 1};
Point(4) = {2, 1, 0, 1};
Point(5) = {1, 1, 0, 1};
Point(6) = {0, 1, 0, 1};
Line(1) = {1, 2};
Line(2) = {2, 5};
Line(3) = {5, 6};
Line(4) = {6, 1};
Line(5) = {2, 3};
Line(6) = {3, 4};
Line(7) = {4, 5};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Curve Loop(2) = {5, 6, 7, -2};
Plane Surface(2) = {2};
Transfinite Curve{1, 2, 3, 4, 5, 6, 7} = n;
Transfinite Surface{1};
Transfinite Surface{2};
Recombine Surface{1};
Physical Curve("bottom") = {1, 5};
Physical Curve("right") = {6};
Physical Point("right") = {3};
Physical Surface("quads") = {1};
Physical Surface("whole") = {1, 2};
