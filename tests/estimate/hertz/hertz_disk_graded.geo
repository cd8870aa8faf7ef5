// Hertz half-disk x^2 + (y-1)^2 <= 1, y <= 1 (master arc), graded: size hc on
// the arc for |x| <= w, growing linearly to hf over the distance g.
DefineConstant[ hc = 0.002, hf = 0.2, w = 0.3, g = 0.5 ];
hf2 = (hf < 0.25) ? hf : 0.25;
th = Asin(w);
Point(1) = {0, 1, 0, hf2};
Point(2) = {-1, 1, 0, hf2};
Point(3) = {-w, 1 - Cos(th), 0, hc};
Point(4) = { w, 1 - Cos(th), 0, hc};
Point(5) = { 1, 1, 0, hf2};
Circle(1) = {2, 1, 3}; Circle(2) = {3, 1, 4}; Circle(3) = {4, 1, 5};
Line(4) = {5, 2};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Field[1] = Distance; Field[1].CurvesList = {2}; Field[1].NumPointsPerCurve = 2000;
Field[2] = Threshold; Field[2].InField = 1; Field[2].SizeMin = hc; Field[2].SizeMax = hf2;
Field[2].DistMin = 0; Field[2].DistMax = g;
Background Field = 2;
Mesh.MeshSizeExtendFromBoundary = 0; Mesh.MeshSizeFromPoints = 0; Mesh.MeshSizeFromCurvature = 0;
Physical Curve("arc") = {1, 2, 3}; Physical Curve("top") = {4};
Physical Surface("disk") = {1};
