// The ring of the axisymmetric drag (axisym.deck): in the (r, z) plane
// the half of a disc of radius R = 10 centred at (rs + R, zc) that faces
// the axis, its flat back on r = rs + R.  Elements hc on the arc within
// |z - zc| < zf of its innermost point, where the contact stays, growing
// to hf away.
DefineConstant[ hc = 0.05, hf = 2, zf = 2, rs = 150, zc = 0 ];
R = 10;
t = Asin(zf / R);
Point(1) = {rs + R, zc, 0, hf};
Point(2) = {rs + R, zc + R, 0, hf};
Point(3) = {rs + R - R * Cos(t), zc + zf, 0, hc};
Point(4) = {rs, zc, 0, hc};
Point(5) = {rs + R - R * Cos(t), zc - zf, 0, hc};
Point(6) = {rs + R, zc - R, 0, hf};
Circle(1) = {2, 1, 3};
Circle(2) = {3, 1, 4};
Circle(3) = {4, 1, 5};
Circle(4) = {5, 1, 6};
Line(5) = {6, 1};
Line(6) = {1, 2};
Curve Loop(1) = {1, 2, 3, 4, 5, 6};
Plane Surface(1) = {1};
Field[1] = Box;
Field[1].VIn = hc;
Field[1].VOut = hf;
Field[1].XMin = rs - 0.1; Field[1].XMax = rs + 1.0;
Field[1].YMin = zc - zf; Field[1].YMax = zc + zf;
Field[1].Thickness = 5;
Background Field = 1;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;
Physical Curve("arc") = {1, 2, 3, 4};
Physical Curve("back") = {5, 6};
Physical Surface("ring") = {1};
