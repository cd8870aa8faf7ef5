// Quarter of a plane-strain O-ring cross-section (x >= 0, y >= 0), radius R,
// centre at the origin.  Size hc within distance Dc of the top point (0, R)
// (where the plate touches; Dc = 2.1 covers the contact zone up to 30 % squeeze),
// growing linearly to hf = min(R/5, 8 hc) at distance Dc + R/2.
// Physical tags: curve 1 = arc (contact), 2 = x = 0 (symmetry ux = 0),
// 3 = y = 0 (symmetry uy = 0), surface 10 = body.
//   gmsh -2 -format msh22 -setnumber hc 0.1 [-order 2] oring_quarter.geo -o q.msh
If (!Exists(hc))
  hc = 0.1;
EndIf
R = 2.5;
Dc = 2.1;
hf = Min(R / 5, 8 * hc);
Point(1) = {0, 0, 0, hf};
Point(2) = {R, 0, 0, hf};
Point(3) = {0, R, 0, hc};
Line(1) = {1, 2};
Circle(2) = {2, 1, 3};
Line(3) = {3, 1};
Curve Loop(1) = {1, 2, 3};
Plane Surface(1) = {1};
Physical Curve(1) = {2};
Physical Curve(2) = {3};
Physical Curve(3) = {1};
Physical Surface(10) = {1};
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
