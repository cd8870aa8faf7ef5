// Unit disk, four counter-clockwise arcs, unstructured triangles of size 0.5.
// Physical curve "rim" only: the surface is in no physical group, so
// Mesh.SaveAll writes its elements (and the unnamed points and lines) anyway.
lc = 0.5;
Point(1) = {0, 0, 0, lc};
Point(2) = {1, 0, 0, lc};
Point(3) = {0, 1, 0, lc};
Point(4) = {-1, 0, 0, lc};
Point(5) = {0, -1, 0, lc};
Circle(1) = {2, 1, 3};
Circle(2) = {3, 1, 4};
Circle(3) = {4, 1, 5};
Circle(4) = {5, 1, 2};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Physical Curve("rim") = {1, 2, 3, 4};
Mesh.SaveAll = 1;
