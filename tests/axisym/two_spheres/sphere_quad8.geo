// A hemisphere of radius R whose pole is the origin, above it (side = 1) or
// below it (side = -1), its r-z section the quarter disk r >= 0, meshed in
// 8-node quadrangles (recombined, second order, serendipity): the elements of
// Code_Aster's SSNA102.  Element size hc in the box r <= bx R, |z| <= bx R
// around the pole, hf far away.
DefineConstant[ hc = 0.01, hf = 0.5, R = 1, side = 1, bx = 0.2 ];
hf2 = (hf < 0.25 * R) ? hf : 0.25 * R;
Point(1) = {0, side * R, 0, hf2};        // centre
Point(2) = {0, 0, 0, hc};                // pole, on the axis
Point(3) = {R, side * R, 0, hf2};        // equator
Circle(1) = {2, 1, 3};
Line(2) = {3, 1};
Line(3) = {1, 2};
Curve Loop(1) = {1, 2, 3};
Plane Surface(1) = {1};
Field[1] = Box;
Field[1].VIn = hc;
Field[1].VOut = hf2;
Field[1].XMin = -0.1 * R; Field[1].XMax = bx * R;
Field[1].YMin = -bx * R; Field[1].YMax = bx * R;
Field[1].Thickness = 0.5 * R;
Background Field = 1;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;
Recombine Surface{1};
Mesh.SecondOrderIncomplete = 1;
Physical Curve("arc") = {1};
Physical Curve("equator") = {2};
Physical Curve("axis") = {3};
Physical Surface("sphere") = {1};
