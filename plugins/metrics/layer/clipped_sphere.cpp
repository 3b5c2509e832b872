#include "clipped_sphere.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace sm = spreadmap;

namespace {

constexpr double pi = std::numbers::pi;

// Antiderivative in x of the slice area {y >= b} of the unit sphere, for a, b >= 0 and x in [0, c],
// c = sqrt(1 - b^2). Derivation: integrate (1 - x^2) acos(b / sqrt(1 - x^2)) by parts; the remaining
// terms are the standard integrals of 1/q, x^2/q, q and 1/((1 - x^2) q), q = sqrt(c^2 - x^2).
double slice_antiderivative(double x, double b, double c) {
  // q = sqrt(c^2 - x^2) = sqrt(1 - x^2 - b^2). acos(b / sqrt(1 - x^2)) and asin(x / c) are written as
  // atan2 of q: acos and asin near 1 would lose half the digits where the plane grazes the sphere.
  const double q = std::sqrt(std::max(0.0, (c - x) * (c + x)));
  const double slice_angle = b == 0 ? pi / 2 : std::atan2(q, b);  // b = 0: half disk at every x
  return (x - x * x * x / 3) * slice_angle - b * (1 - b * b / 3) * std::atan2(x, q) - 2.0 / 3.0 * b * x * q +
         2.0 / 3.0 * std::atan2(b * x, q);
}

}  // namespace

double sm::layer::unit_sphere_cap_volume(double t) {
  if (t >= 1) return 0;
  if (t <= -1) return 4 * pi / 3;
  return pi * (1 - t) * (1 - t) * (2 + t) / 3;
}

double sm::layer::unit_sphere_quadrant_volume(double a, double b) {
  // Reflections bring both planes to the positive side: {y >= b} = all - {y < b} = cap - {y >= -b}.
  if (b < 0) return unit_sphere_cap_volume(a) - unit_sphere_quadrant_volume(a, -b);
  if (a < 0) return unit_sphere_cap_volume(b) - unit_sphere_quadrant_volume(-a, b);
  if (a * a + b * b >= 1) return 0;
  const double c = std::sqrt(1 - b * b);  // largest x at which the plane y = b still cuts the sphere
  return slice_antiderivative(c, b, c) - slice_antiderivative(a, b, c);
}

double sm::layer::sphere_volume_in_prism(double xc, double yc, double r, double x0, double x1, double y0, double y1) {
  if (r <= 0 || x1 <= x0 || y1 <= y0) return 0;
  if (xc + r <= x0 || xc - r >= x1 || yc + r <= y0 || yc - r >= y1) return 0;
  const double whole = 4 * pi / 3 * r * r * r;
  if (xc - r >= x0 && xc + r <= x1 && yc - r >= y0 && yc + r <= y1) return whole;
  const double a0 = (x0 - xc) / r, a1 = (x1 - xc) / r, b0 = (y0 - yc) / r, b1 = (y1 - yc) / r;
  const double unit = unit_sphere_quadrant_volume(a0, b0) - unit_sphere_quadrant_volume(a1, b0) -
                      unit_sphere_quadrant_volume(a0, b1) + unit_sphere_quadrant_volume(a1, b1);
  return std::clamp(unit, 0.0, 4 * pi / 3) * r * r * r;
}
