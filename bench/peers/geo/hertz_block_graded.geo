// Hertz problem H, the block of input/hertz_block.geo, with the contact line
// |x| <= 0.3 of its top as the physical curve "contact" (the slave: the disk's
// arc then covers the whole slave, which quadratic traces need), and, with
// graded = 1, graded toward the contact zone's ends: element size hz at the
// points (+-a, 0), growing linearly at rate g with the distance to the nearer
// one, capped by the size of input/hertz_block.geo (hc in its box around the
// zone, hf far away).  The pressure's square-root ends hold an even mesh to
// O(h) in L2; this mesh puts the small elements where the pressure is not
// smooth.
DefineConstant[ a = 0.08, hz = 0.001, g = 0.2, graded = 1 ];
Include "../../../input/hertz_block.geo";
Physical Curve("contact") = {4};
If (graded)
  Field[2] = MathEval;
  Field[2].F = Sprintf("%.10g + %.10g * Sqrt((Fabs(x) - %.10g)^2 + y^2)", hz, g, a);
  Field[3] = Min;
  Field[3].FieldsList = {1, 2};
  Background Field = 3;
EndIf
