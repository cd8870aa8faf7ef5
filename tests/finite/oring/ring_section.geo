// Half of an O-ring's cross-section (y >= 0, the mid-plane y = 0 a symmetry
// line) of radius R = 2.5 (d = 5) centred at (r0, 0), for PLANE
// axisymmetric (x = r), in quadrangles (F-bar).  Size hc within Dc of the
// top point (0 + r0, R), where the plate touches, growing to min(R/5, 8 hc)
// at Dc + R/2.  Boundaries: arc (contact), base (y = 0), the point centre
// (r0, 0).
If (!Exists(hc))
  hc = 0.1;
EndIf
If (!Exists(r0))
  r0 = 200;
EndIf
R = 2.5;
Dc = 2.1;
hf = Min(R / 5, 8 * hc);
Point(1) = {r0, 0, 0, hf};
Point(2) = {r0 + R, 0, 0, hf};
Point(3) = {r0, R, 0, hc};
Point(4) = {r0 - R, 0, 0, hf};
Line(1) = {4, 1};
Line(2) = {1, 2};
Circle(3) = {2, 1, 3};
Circle(4) = {3, 1, 4};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Physical Curve("arc") = {3, 4};
Physical Curve("base") = {1, 2};
Physical Point("centre") = {1};
Physical Surface("ring") = {1};
Field[1] = Distance;
Field[1].PointsList = {3};
Field[2] = Threshold;
Field[2].InField = 1;
Field[2].SizeMin = hc;
Field[2].SizeMax = hf;
Field[2].DistMin = Dc;
Field[2].DistMax = Dc + R / 2;
Background Field = 2;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;
Recombine Surface{1};
