// Quarter annulus r in [1, 2], theta in [0, 90] degrees: two circle arcs, so a
// second-order mesh (gmsh -order 2) has curved edges with the mid-side nodes on
// the arcs.  quads = 1 recombines into quadrangles; incomplete = 1 makes them
// 8-node (serendipity) instead of 9-node at -order 2.  n: nodes per side.
DefineConstant[ n = 4, quads = 0, incomplete = 0 ];
Mesh.SecondOrderIncomplete = incomplete;
Point(1) = {0, 0, 0, 1};
Point(2) = {1, 0, 0, 1};
Point(3) = {2, 0, 0, 1};
Point(4) = {0, 2, 0, 1};
Point(5) = {0, 1, 0, 1};
Line(1) = {2, 3};
Circle(2) = {3, 1, 4};
Line(3) = {4, 5};
Circle(4) = {5, 1, 2};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Transfinite Curve{1, 3} = n;
Transfinite Curve{2, 4} = n + 1;
If (quads)
  Recombine Surface{1};
EndIf
Physical Curve("bottom") = {1};
Physical Curve("outer") = {2};
Physical Curve("left") = {3};
Physical Curve("inner") = {4};
Physical Surface("body") = {1};
