// Unit square [0,1]^2, structured: n nodes per side, 2 (n-1)^2 triangles.
// Physical curves bottom/right/top/left, physical point "corner" at (0,0),
// physical surfaces "body" and 7 (unnamed) over the same surface.
DefineConstant[ n = 4 ];
Point(1) = {0, 0, 0, 1};
Point(2) = {1, 0, 0, 1};
Point(3) = {1, 1, 0, 1};
Point(4) = {0, 1, 0, 1};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Transfinite Curve{1, 2, 3, 4} = n;
Transfinite Surface{1};
Physical Curve("bottom") = {1};
Physical Curve("right") = {2};
Physical Curve("top") = {3};
Physical Curve("left") = {4};
Physical Point("corner") = {1};
Physical Surface("body") = {1};
Physical Surface(7) = {1};
