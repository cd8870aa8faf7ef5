// A block with a V-groove of half-angle theta (degrees from the vertical)
// whose flanks touch the circle of radius R about the origin at
// R (+-cos theta, -sin theta) (points 5 and 7): the apex at (0, -R / sin
// theta), the top at y = -15, the bottom at y = -140, |x| <= 130.  Element
// size hc within 5 of either contact point, growing to hf beyond 40.  The
// two flanks named as one boundary, "vee" (one contact pair touches both).
DefineConstant[ R = 50, theta = 60, hc = 0.3, hf = 8 ];
t = theta * Pi / 180;
yt = -15;
ya = -R / Sin(t);
xt = (yt - ya) * Tan(t);
Point(1) = {-130, -140, 0, hf};
Point(2) = { 130, -140, 0, hf};
Point(3) = { 130, yt, 0, hf};
Point(4) = { xt, yt, 0, hf};
Point(5) = { R * Cos(t), -R * Sin(t), 0, hc};
Point(6) = { 0, ya, 0, hf};
Point(7) = {-R * Cos(t), -R * Sin(t), 0, hc};
Point(8) = {-xt, yt, 0, hf};
Point(9) = {-130, yt, 0, hf};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 5};
Line(5) = {5, 6}; Line(6) = {6, 7}; Line(7) = {7, 8}; Line(8) = {8, 9}; Line(9) = {9, 1};
Curve Loop(1) = {1:9};
Plane Surface(1) = {1};
Field[1] = Distance;
Field[1].PointsList = {5, 7};
Field[2] = Threshold;
Field[2].InField = 1;
Field[2].SizeMin = hc; Field[2].SizeMax = hf;
Field[2].DistMin = 5; Field[2].DistMax = 40;
Background Field = 2;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;
Physical Surface("vblock") = {1};
Physical Curve("vee") = {4:7};
Physical Curve("bottom") = {1};
