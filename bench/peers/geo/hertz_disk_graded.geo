// Hertz problem H, the disk of input/hertz_disk.geo graded toward the contact
// zone's ends: element size hz at the points (+-a, 1 - sqrt(1 - a^2)) of the
// arc, growing linearly at rate g with the distance to the nearer one, capped
// by the size of input/hertz_disk.geo (hc in its box around the zone, hf far
// away).  The pressure's square-root ends hold an even mesh to O(h) in L2;
// this mesh puts the small elements where the pressure is not smooth.  The
// points are on the arc, not at (+-a, 0): the arc passes 1 - sqrt(1 - a^2)
// (0.00245 at a = 0.07) above those, so a grading aimed there leaves the
// disk's elements at the zone's ends no smaller than g times that, whatever
// hz, and the master's size there sets where the discrete zone ends.
DefineConstant[ a = 0.08, hz = 0.001, g = 0.2 ];
Include "../../../input/hertz_disk.geo";
Field[2] = MathEval;
Field[2].F = Sprintf("%.10g + %.10g * Sqrt((Fabs(x) - %.10g)^2 + (y - %.10g)^2)", hz, g, a, 1 - Sqrt(1 - a^2));
Field[3] = Min;
Field[3].FieldsList = {1, 2};
Background Field = 3;
