// A cylinder (disk) of radius R centred at the origin, for a V-groove of
// half-angle theta (degrees from the vertical): it touches the flanks at
// R (+-cos theta, -sin theta), points 4 and 6 of the rim.  Element size hc
// within 5 of either point, growing to hf beyond 40; the rim named as a
// whole (a closed curve), the centre a point for the load, the top one
// to hold the rotation (frictionless contact on a circle does not).
DefineConstant[ R = 50, theta = 60, hc = 0.3, hf = 8 ];
t = theta * Pi / 180;
Point(1) = {0, 0, 0, hf};
Point(2) = {R, 0, 0, hf};
Point(3) = {0, R, 0, hf};
Point(4) = {-R, 0, 0, hf};
Point(5) = {-R * Cos(t), -R * Sin(t), 0, hc};
Point(6) = {0, -R, 0, hf};
Point(7) = {R * Cos(t), -R * Sin(t), 0, hc};
Circle(1) = {2, 1, 3}; Circle(2) = {3, 1, 4}; Circle(3) = {4, 1, 5};
Circle(4) = {5, 1, 6}; Circle(5) = {6, 1, 7}; Circle(6) = {7, 1, 2};
Curve Loop(1) = {1:6};
Plane Surface(1) = {1};
Point{1} In Surface{1};
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
Physical Surface("disk") = {1};
Physical Curve("rim") = {1:6};
Physical Point("centre") = {1};
Physical Point("top") = {3};
