// Signorini problem S, one block [0,2] x [y0, y0+1] meshed by triangles of
// size hs along the contact edge (y = 1), growing linearly to hb at the
// distance d from it: many contact nodes for few dofs (the LCP cost sweep).
// y0 = 0: the lower block (contact edge on top); y0 = 1: the upper block.
DefineConstant[ hs = 0.01, hb = 0.05, d = 0.5, y0 = 0 ];
Point(1) = {0, y0, 0, hb};
Point(2) = {2, y0, 0, hb};
Point(3) = {2, y0 + 1, 0, hb};
Point(4) = {0, y0 + 1, 0, hb};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Field[1] = MathEval;
Field[1].F = Sprintf("%.17g + %.17g * Min(1, Fabs(y - 1) / %.17g)", hs, hb - hs, d);
Background Field = 1;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;
Physical Curve("bottom") = {1};
Physical Curve("right") = {2};
Physical Curve("top") = {3};
Physical Curve("left") = {4};
Physical Surface("block") = {1};
