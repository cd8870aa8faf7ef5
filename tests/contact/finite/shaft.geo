// The shaft of the axisymmetric drag (axisym.deck): a thick tube in the
// (r, z) plane, r in [rs - 100, rs], z in [-100, 100], held on its inner
// face.  Elements hc along the ring's path on its outer face, z in
// [z0, z1], growing to hf away from it.
DefineConstant[ hc = 0.05, hf = 20, rs = 150, z0 = -6, z1 = 2 ];
Point(1) = {rs - 100, -100, 0, hf};
Point(2) = {rs, -100, 0, hf};
Point(3) = {rs, z0, 0, hc};
Point(4) = {rs, z1, 0, hc};
Point(5) = {rs, 100, 0, hf};
Point(6) = {rs - 100, 100, 0, hf};
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
Field[1].XMin = rs - 1.0; Field[1].XMax = rs + 0.1;
Field[1].YMin = z0; Field[1].YMax = z1;
Field[1].Thickness = 30;
Background Field = 1;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;
Physical Curve("inner") = {6};
Physical Curve("outer") = {2, 3, 4};
Physical Curve("ends") = {1, 5};
Physical Surface("shaft") = {1};
