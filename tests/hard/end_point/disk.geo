// Half-disk x^2 + (y-1)^2 <= 1, y <= 1 (the upper body), element size hc on
// |x| <= w, y <= d next to its lowest point (0,0), growing to hf away.
DefineConstant[ hc = 0.01, hf = 0.25, w = 0.15, d = 0.08 ];
Point(1) = { 0, 1, 0, hf};
Point(2) = {-1, 1, 0, hf};
Point(3) = { 0, 0, 0, hc};
Point(4) = { 1, 1, 0, hf};
Circle(1) = {2, 1, 3};
Circle(2) = {3, 1, 4};
Line(3) = {4, 2};
Curve Loop(1) = {1, 2, 3};
Plane Surface(1) = {1};
Field[1] = Box;
Field[1].VIn = hc;
Field[1].VOut = hf;
Field[1].XMin = -w; Field[1].XMax = w;
Field[1].YMin = -0.1; Field[1].YMax = d;
Field[1].Thickness = 0.4;
Background Field = 1;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;
Physical Curve("arc") = {1, 2};
Physical Curve("top") = {3};
Physical Surface("disk") = {1};
