// The deformable roller of the finite-sliding drag (drag.deck): the lower
// half of a disc of radius R = 10 centred at (xs, 10), its flat top on the
// diameter.  Elements hc on the arc within |x - xs| < xf of its lowest
// point, where the contact stays (the roller translates), growing to hf
// away.  xs places the roller elsewhere from the start (placed.deck).
DefineConstant[ hc = 0.05, hf = 2, xf = 2, xs = 0 ];
R = 10;
t = Asin(xf / R);
Point(1) = {xs, R, 0, hf};
Point(2) = {xs - R, R, 0, hf};
Point(3) = {xs - xf, R - R * Cos(t), 0, hc};
Point(4) = {xs, 0, 0, hc};
Point(5) = {xs + xf, R - R * Cos(t), 0, hc};
Point(6) = {xs + R, R, 0, hf};
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
Field[1].XMin = xs - xf; Field[1].XMax = xs + xf;
Field[1].YMin = -0.1; Field[1].YMax = 1.0;
Field[1].Thickness = 5;
Background Field = 1;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;
Physical Curve("arc") = {1, 2, 3, 4};
Physical Curve("top") = {5, 6};
Physical Surface("roller") = {1};
