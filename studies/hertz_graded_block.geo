// Hertz problem H, body 1 (slave): the block [-4,4] x [-4,0], as
// input/hertz_block.geo, graded toward the contact zone's ends x = +-a: size
// ge hc at the two points, growing by half the distance to hc.
DefineConstant[ hc = 0.02, hf = 0.5, a = 0.0705, ge = 0.125 ];
Point(1) = {-4, -4, 0, hf};
Point(2) = { 4, -4, 0, hf};
Point(3) = { 4,  0, 0, hf};
Point(4) = { 0.3, 0, 0, hc};
Point(5) = {-0.3, 0, 0, hc};
Point(6) = {-4,  0, 0, hf};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 5};
Line(5) = {5, 6};
Line(6) = {6, 1};
Curve Loop(1) = {1, 2, 3, 4, 5, 6};
Plane Surface(1) = {1};
Field[1] = Box;
Field[1].VIn = hc;
Field[1].VOut = hf;
Field[1].XMin = -0.3; Field[1].XMax = 0.3;
Field[1].YMin = -0.3; Field[1].YMax = 0.1;
Field[1].Thickness = 1.5;
Point(10) = {-a, 0, 0, hc};
Point(11) = { a, 0, 0, hc};
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
Physical Curve("bottom") = {1};
Physical Curve("right") = {2};
Physical Curve("top") = {3, 4, 5};
Physical Curve("left") = {6};
Physical Surface("block") = {1};
