// Half of an O-ring's cross-section (x >= 0, the line x = 0 a symmetry
// line), radius R = 2.5 (d = 5) centred at the origin, quadrangles of size
// hc.  Boundaries: arc (the rim, x >= 0), axis (x = 0), the point centre.
If (!Exists(hc))
  hc = 0.1;
EndIf
R = 2.5;
Point(1) = {0, 0, 0, hc};
Point(2) = {0, R, 0, hc};
Point(3) = {R, 0, 0, hc};
Point(4) = {0, -R, 0, hc};
Circle(1) = {4, 1, 3};
Circle(2) = {3, 1, 2};
Line(3) = {2, 1};
Line(4) = {1, 4};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Physical Curve("arc") = {1, 2};
Physical Curve("axis") = {3, 4};
Physical Point("centre") = {1};
Physical Surface("ring") = {1};
Recombine Surface{1};
