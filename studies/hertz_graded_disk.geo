// Hertz problem H, body 2 (master): the half-disk x^2 + (y-1)^2 <= 1, y <= 1,
// as input/hertz_disk.geo, graded toward the contact zone's ends x = +-a:
// size ge hc at the two points of the arc, growing by half the distance to hc.
DefineConstant[ hc = 0.02, hf = 0.5, a = 0.0705, ge = 0.125 ];
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
Point(10) = {-a, 1 - Sqrt(1 - a * a), 0, hc};
Point(11) = { a, 1 - Sqrt(1 - a * a), 0, hc};
Field[2] = Distance;
Field[2].PointsList = {10, 11};
Field[3] = Threshold;
Field[3].InField = 2;
Field[3].SizeMin = ge * hc;
Field[3].SizeMax = hc;
Field[3].DistMin = ge * hc;
Field[3].DistMax = ge * hc + 2 * (1 - ge) * hc;
Field[3].StopAtDistMax = 1;   // beyond it the Box field alone
Field[4] = Min;
Field[4].FieldsList = {1, 3};
Background Field = 4;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;
Physical Curve("arc") = {1, 2};
Physical Curve("top") = {3};
Physical Surface("disk") = {1};
