// Two layers of a bar [0,2] x [0,1]: physical surfaces "lower" (y < 0.5) and
// "upper" (y > 0.5), unstructured triangles of size h.
DefineConstant[ h = 0.1 ];
Point(1) = {0, 0, 0, h};  Point(2) = {2, 0, 0, h};
Point(3) = {2, 0.5, 0, h}; Point(4) = {0, 0.5, 0, h};
Point(5) = {2, 1, 0, h};  Point(6) = {0, 1, 0, h};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Line(5) = {3, 5}; Line(6) = {5, 6}; Line(7) = {6, 4};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
Curve Loop(2) = {-3, 5, 6, 7}; Plane Surface(2) = {2};
Physical Curve("bottom") = {1};
Physical Curve("right") = {2, 5};
Physical Curve("left") = {4, 7};
Physical Curve("top") = {6};
Physical Surface("lower") = {1};
Physical Surface("upper") = {2};
