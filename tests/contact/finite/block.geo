// The block [-100,100] x [-100,0] of the finite-sliding drag (drag.deck):
// element size hc along the cylinder's path on its top edge, x in [x0, x1],
// growing to hf away from it, so that the block is large against the
// contact zone (a = 0.76) at a few thousand elements.
DefineConstant[ hc = 0.05, hf = 20, x0 = -2, x1 = 6 ];
Point(1) = {-100, -100, 0, hf};
Point(2) = { 100, -100, 0, hf};
Point(3) = { 100,  0, 0, hf};
Point(4) = { x1, 0, 0, hc};
Point(5) = { x0, 0, 0, hc};
Point(6) = {-100,  0, 0, hf};
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
Field[1].XMin = x0; Field[1].XMax = x1;
Field[1].YMin = -1.0; Field[1].YMax = 0.1;
Field[1].Thickness = 30;
Background Field = 1;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;
Physical Curve("bottom") = {1};
Physical Curve("right") = {2};
Physical Curve("top") = {3, 4, 5};
Physical Curve("left") = {6};
Physical Surface("block") = {1};
