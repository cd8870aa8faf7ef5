// The unit square [0,1] x [0,1] rotated by `angle` degrees about the
// origin, unstructured triangles of size h; physical curves bottom, right,
// top, left as those of the unrotated square.
DefineConstant[ y0 = 0, h = 0.2, angle = 30 ];
c = Cos(angle * Pi / 180); s = Sin(angle * Pi / 180);
Point(1) = {0 * c - y0 * s, 0 * s + y0 * c, 0, h};
Point(2) = {1 * c - y0 * s, 1 * s + y0 * c, 0, h};
Point(3) = {1 * c - (y0 + 1) * s, 1 * s + (y0 + 1) * c, 0, h};
Point(4) = {0 * c - (y0 + 1) * s, 0 * s + (y0 + 1) * c, 0, h};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
Physical Curve("bottom") = {1};
Physical Curve("right") = {2};
Physical Curve("top") = {3};
Physical Curve("left") = {4};
Physical Surface("block") = {1};
