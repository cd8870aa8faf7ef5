// Axisymmetric Hertz: the flat block 0 <= r <= 4, -4 <= z <= 0 (slave),
// the r-z section of a cylinder of radius 4 and height 4.
// Element size hc on r <= 0.2 near the top edge, hf far away.
DefineConstant[ hc = 0.004, hf = 0.5 ];
Point(1) = {0, -4, 0, hf};
Point(2) = {4, -4, 0, hf};
Point(3) = {4,  0, 0, hf};
Point(4) = {0.2, 0, 0, hc};
Point(5) = {0,  0, 0, hc};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 5};
Line(5) = {5, 1};
Curve Loop(1) = {1, 2, 3, 4, 5};
Plane Surface(1) = {1};
Field[1] = Box;
Field[1].VIn = hc;
Field[1].VOut = hf;
Field[1].XMin = -0.1; Field[1].XMax = 0.2;
Field[1].YMin = -0.2; Field[1].YMax = 0.1;
Field[1].Thickness = 1.0;
Background Field = 1;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;
Physical Curve("bottom") = {1};
Physical Curve("right") = {2};
Physical Curve("top") = {3, 4};
Physical Curve("axis") = {5};
Physical Surface("block") = {1};
