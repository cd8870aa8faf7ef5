// Quarter of a plane-strain O-ring cross-section (x >= 0, y >= 0), radius
// R = 2.5 (d = 5), centre at the origin: the mesh of bench/oring's GetFEM
// reference with named boundaries.  Size hc within Dc of the top point
// (0, R), where the plate touches (Dc = 2.1 covers the zone up to 30 %
// squeeze), growing to hf = min(R/5, 8 hc) at Dc + R/2.  quads = 1:
// quadrangles (recombined), for the F-bar of nearly incompressible rubber;
// packed = 1 makes them nearly structured (below).
// Boundaries: arc (contact), axis (x = 0, symmetry), base (y = 0, symmetry).
If (!Exists(hc))
  hc = 0.1;
EndIf
If (!Exists(quads))
  quads = 0;
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
Physical Curve("arc") = {2};
Physical Curve("axis") = {3};
Physical Curve("base") = {1};
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
If (!Exists(packed))
  packed = 0;
EndIf
If (quads)
  // packed = 1: gmsh's packing of parallelograms, nearly structured
  // quadrangles.  On the recombined Frontal-Delaunay triangles (packed = 0)
  // F-bar's element pressures scatter with the elements' shapes, and the
  // nodal contact pressure with them: the peak pressure at 10 % squeeze
  // moves by +-0.1 % from one size to the next (doc/accuracy-cost.md).  At
  // coarse sizes (hc = 0.2) the packed mesh is the worse of the two.
  If (packed)
    Mesh.Algorithm = 9;
  EndIf
  Recombine Surface{1};
EndIf
