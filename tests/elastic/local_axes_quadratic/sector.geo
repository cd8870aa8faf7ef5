// A quarter of the annulus a <= r <= b turned by t0 degrees: the radial
// sides "start" (at t0) and "end" (at t0 + 90) are straight and along no
// axis, the arcs "inner" and "outer" are circles, so a second-order mesh
// (gmsh -order 2) has its boundary mid-side nodes on them.  quads = 1
// recombines into quadrangles; incomplete = 1 makes them 8-node at -order 2.
// n: nodes along a radial side, m: along an arc.
DefineConstant[ t0 = 30, a = 1, b = 2, n = 5, m = 6, quads = 1, incomplete = 0 ];
Mesh.SecondOrderIncomplete = incomplete;
c0 = Cos(t0 * Pi / 180); s0 = Sin(t0 * Pi / 180);
c1 = Cos((t0 + 90) * Pi / 180); s1 = Sin((t0 + 90) * Pi / 180);
Point(1) = {0, 0, 0, 1};
Point(2) = {a * c0, a * s0, 0, 1};
Point(3) = {b * c0, b * s0, 0, 1};
Point(4) = {b * c1, b * s1, 0, 1};
Point(5) = {a * c1, a * s1, 0, 1};
Line(1) = {2, 3};
Circle(2) = {3, 1, 4};
Line(3) = {4, 5};
Circle(4) = {5, 1, 2};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Transfinite Curve{1, 3} = n;
Transfinite Curve{2, 4} = m;
Transfinite Surface{1};
If (quads)
  Recombine Surface{1};
EndIf
Physical Curve("start") = {1};
Physical Curve("outer") = {2};
Physical Curve("end") = {3};
Physical Curve("inner") = {4};
Physical Surface("body") = {1};
