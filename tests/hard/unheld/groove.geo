// A foundation with a V groove on top: (-1, 0.5) - (0, 0) - (1, 0.5), the
// groove's faces at atan(1/2) to the horizontal (a true corner at the origin).
DefineConstant[ h = 0.1 ];
Point(1) = {-1, -1, 0, h};
Point(2) = { 1, -1, 0, h};
Point(3) = { 1, 0.5, 0, h};
Point(4) = { 0, 0, 0, h};
Point(5) = {-1, 0.5, 0, h};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 5};
Line(5) = {5, 1};
Curve Loop(1) = {1, 2, 3, 4, 5};
Plane Surface(1) = {1};
Physical Curve("bottom") = {1};
Physical Curve("groove") = {3, 4};
Physical Surface("foundation") = {1};
