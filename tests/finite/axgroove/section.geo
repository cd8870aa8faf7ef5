// An O-ring's whole cross-section for PLANE axisymmetric (x = r, y = z):
// radius R = 2.5 (d = 5) centred at (r0, R), so that it rests on z = 0;
// quadrangles of size hc.  Its whole rim is one boundary, "rim".
If (!Exists(hc))
  hc = 0.3;
EndIf
If (!Exists(r0))
  r0 = 20;
EndIf
R = 2.5;
Point(1) = {r0, R, 0, hc};
Point(2) = {r0 + R, R, 0, hc};
Point(3) = {r0, 2 * R, 0, hc};
Point(4) = {r0 - R, R, 0, hc};
Point(5) = {r0, 0, 0, hc};
Circle(1) = {2, 1, 3};
Circle(2) = {3, 1, 4};
Circle(3) = {4, 1, 5};
Circle(4) = {5, 1, 2};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Physical Curve("rim") = {1, 2, 3, 4};
Physical Surface("ring") = {1};
Recombine Surface{1};
