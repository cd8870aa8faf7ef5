// A block with a V bottom (-0.8, 0.4) - (0, 0) - (0.8, 0.4) that fits the
// groove of groove.geo, top at y = 1.
DefineConstant[ h = 0.07 ];
Point(1) = { 0, 0, 0, h};
Point(2) = { 0.8, 0.4, 0, h};
Point(3) = { 0.8, 1, 0, h};
Point(4) = {-0.8, 1, 0, h};
Point(5) = {-0.8, 0.4, 0, h};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 5};
Line(5) = {5, 1};
Curve Loop(1) = {1, 2, 3, 4, 5};
Plane Surface(1) = {1};
Physical Curve("vee") = {5, 1};
Physical Curve("top") = {3};
Physical Surface("wedge") = {1};
