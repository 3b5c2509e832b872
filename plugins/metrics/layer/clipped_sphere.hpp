// Volume of a sphere inside an axis-aligned box in x-y (a vertical prism: unbounded in z).
//
// Closed form, exact to round-off. With the unit sphere, W(a, b) = volume where x >= a and y >= b is
// an antiderivative evaluated at the ends of the x range (integrating circle-segment areas
// s^2 acos(b/s) - b sqrt(s^2 - b^2), s^2 = 1 - x^2, by parts); a box follows by inclusion-exclusion:
// V = W(a0,b0) - W(a1,b0) - W(a0,b1) + W(a1,b1). SI units in and out.
#pragma once

namespace spreadmap::layer {

// Unit sphere: volume of {x >= t}, a spherical cap of height 1 - t (any t).
double unit_sphere_cap_volume(double t);

// Unit sphere: volume of {x >= a, y >= b}. Any a, b (negative and beyond +-1 included).
double unit_sphere_quadrant_volume(double a, double b);

// Sphere (centre xc, yc, radius r) clipped by x0 <= x <= x1 and y0 <= y <= y1 [m^3].
double sphere_volume_in_prism(double xc, double yc, double r, double x0, double x1, double y0, double y1);

}  // namespace spreadmap::layer
