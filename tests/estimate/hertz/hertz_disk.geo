// Hertz problem H, body 2 (master): the half-disk x^2 + (y-1)^2 <= 1, y <= 1.
// Element size hc on |x| <= 0.3 near the lowest point (0,0), hf far away.
DefineConstant[ hc = 0.02, hf = 0.5 ];
hf2 = (hf < 0.25) ? hf : 0.25;   // the disk is small: at most 0.25 far away
Point(1) = { 0, 1, 0, hf2};      // centre
Point(2) = {-1, 1, 0, hf2};
Point(3) = { 0, 0, 0, hc};
Point(4) = { 1, 1, 0, hf2};
Circle(1) = {2, 1, 3};
Circle(2) = {3, 1, 4};
Line(3) = {4, 2};
Curve Loop(1) = {1, 2, 3};
Plane Surface(1) = {1};
Field[1] = Box;
Field[1].VIn = hc;
Field[1].VOut = hf2;
Field[1].XMin = -0.3; Field[1].XMax = 0.3;
Field[1].YMin = -0.1; Field[1].YMax = 0.3;
Field[1].Thickness = 0.5;
Background Field = 1;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;
Physical Curve("arc") = {1, 2};
Physical Curve("top") = {3};
Physical Surface("disk") = {1};
