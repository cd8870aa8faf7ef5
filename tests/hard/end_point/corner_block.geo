// Block [-1,0] x [-1,0] (the lower body) whose top-right corner (0,0) is the
// end node a2 of its top edge; element size hc on -w <= x <= 0, -d <= y <= 0,
// growing to hf away (boundaries bottom, right, top, left).
DefineConstant[ hc = 0.01, hf = 0.25, w = 0.15, d = 0.08 ];
Point(1) = {-1, -1, 0, hf};
Point(2) = { 0, -1, 0, hf};
Point(3) = { 0,  0, 0, hc};
Point(4) = {-w,  0, 0, hc};
Point(5) = {-1,  0, 0, hf};
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
Field[1].XMin = -w; Field[1].XMax = 0.1;
Field[1].YMin = -d; Field[1].YMax = 0.1;
Field[1].Thickness = 0.4;
Background Field = 1;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;
Physical Curve("bottom") = {1};
Physical Curve("right") = {2};
Physical Curve("top") = {3, 4};
Physical Curve("left") = {5};
Physical Surface("block") = {1};
