// Hertz block [-4,4] x [-4,0] (slave top edge), graded: size hc on the top
// edge for |x| <= w, growing linearly to hf over the distance g.
DefineConstant[ hc = 0.002, hf = 0.2, w = 0.3, g = 0.5 ];
Point(1) = {-4, -4, 0, hf};
Point(2) = { 4, -4, 0, hf};
Point(3) = { 4,  0, 0, hf};
Point(4) = { w, 0, 0, hc};
Point(5) = {-w, 0, 0, hc};
Point(6) = {-4,  0, 0, hf};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 5}; Line(5) = {5, 6}; Line(6) = {6, 1};
Curve Loop(1) = {1, 2, 3, 4, 5, 6};
Plane Surface(1) = {1};
Field[1] = Distance; Field[1].CurvesList = {4}; Field[1].NumPointsPerCurve = 2000;
Field[2] = Threshold; Field[2].InField = 1; Field[2].SizeMin = hc; Field[2].SizeMax = hf;
Field[2].DistMin = 0; Field[2].DistMax = g;
Background Field = 2;
Mesh.MeshSizeExtendFromBoundary = 0; Mesh.MeshSizeFromPoints = 0; Mesh.MeshSizeFromCurvature = 0;
Physical Curve("bottom") = {1}; Physical Curve("right") = {2}; Physical Curve("top") = {3, 4, 5}; Physical Curve("left") = {6};
Physical Surface("block") = {1};
