// Unit square [0,1] x [y0, y0+1], unstructured triangles of size h
// (boundaries bottom, right, top, left), for the perturbed patch test.
DefineConstant[ h = 0.15, y0 = 0 ];
Point(1) = {0, y0, 0, h};
Point(2) = {1, y0, 0, h};
Point(3) = {1, y0 + 1, 0, h};
Point(4) = {0, y0 + 1, 0, h};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Physical Curve("bottom") = {1};
Physical Curve("right") = {2};
Physical Curve("top") = {3};
Physical Curve("left") = {4};
Physical Surface("square") = {1};
