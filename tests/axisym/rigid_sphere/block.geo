// An axisymmetric block 0 <= r <= L, -L <= z <= 0 (the r-z section of a
// cylinder of radius L and height L), elements of hc within rc of the top's
// centre (r, z) = (0, 0), growing to hf at a distance L / 2.
DefineConstant[ L = 20, hc = 0.02, rc = 0.7, hf = 2 ];
Point(1) = {0, -L, 0, hf};
Point(2) = {L, -L, 0, hf};
Point(3) = {L,  0, 0, hf};
Point(4) = {0,  0, 0, hc};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Field[1] = Distance;
Field[1].PointsList = {4};
Field[2] = Threshold;
Field[2].InField = 1;
Field[2].SizeMin = hc;
Field[2].SizeMax = hf;
Field[2].DistMin = rc;
Field[2].DistMax = L / 2;
Background Field = 2;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;
Physical Curve("bottom") = {1};
Physical Curve("right") = {2};
Physical Curve("top") = {3};
Physical Curve("axis") = {4};
Physical Surface("block") = {1};
