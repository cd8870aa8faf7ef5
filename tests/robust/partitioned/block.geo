// The upper block of a contact patch, [0,1] x [1,1.6] with a bump of
// element sizes so that gmsh -part has uneven partitions to cut.
DefineConstant[ h = 0.08 ];
Point(1) = {0, 1, 0, h}; Point(2) = {1, 1, 0, h / 2};
Point(3) = {1, 1.6, 0, h}; Point(4) = {0, 1.6, 0, h};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
Physical Curve("bottom") = {1}; Physical Curve("right") = {2};
Physical Curve("top") = {3}; Physical Curve("left") = {4};
Physical Surface("block") = {1};
