// An axisymmetric ring section [r0, r1] x [0, len] (x = r, y = z), unstructured
// triangles of size h; boundaries bottom (z = 0), top (z = len), inner (r = r0), outer (r = r1).
DefineConstant[ r0 = 0, r1 = 1, len = 0.5, h = 0.1 ];
Point(1) = {r0, 0, 0, h}; Point(2) = {r1, 0, 0, h}; Point(3) = {r1, len, 0, h}; Point(4) = {r0, len, 0, h};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Physical Curve("bottom") = {1}; Physical Curve("outer") = {2}; Physical Curve("top") = {3}; Physical Curve("inner") = {4};
Physical Surface("ring") = {1};
