// Volume of a sphere cut by the sampling region's vertical planes (solid_thickness relies on it).
// References are independent closed forms (half sphere, cap, quarter) and a numerical integration of
// circle-segment areas; the requirement is 1e-9 relative, the closed form reaches round-off.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "clipped_sphere.hpp"

namespace {

using spreadmap::layer::sphere_volume_in_prism;
using spreadmap::layer::unit_sphere_quadrant_volume;
constexpr double pi = std::numbers::pi;
constexpr double r = 125e-6, xc = 3e-3, yc = -2e-3;  // a powder grain away from the origin
constexpr double far = 1.0;                          // a plane that does not cut
const double whole = 4 * pi / 3 * r * r * r;

double cap(double h) { return pi * h * h * (3 * r - h) / 3; }  // cap of height h

// Area of the disk of radius s where y >= t, and its 1-D integral over x in [lo, hi] for the unit
// sphere, by Gauss-Legendre on pieces split where the integrand is not smooth, each mapped with
// x = mid - half cos(u) so that sqrt-type end behaviour becomes smooth.
double segment_above(double s, double t) {
  if (t >= s) return 0;
  if (t <= -s) return pi * s * s;
  return s * s * std::acos(t / s) - t * std::sqrt(s * s - t * t);
}
double numeric_box_volume(double a0, double a1, double b0, double b1) {
  static const double node[8] = {-0.9602898564975363, -0.7966664774136267, -0.5255324099163290, -0.1834346424956498,
                                 0.1834346424956498,  0.5255324099163290,  0.7966664774136267,  0.9602898564975363};
  static const double weight[8] = {0.1012285362903763, 0.2223810344533745, 0.3137066458778873, 0.3626837833783620,
                                   0.3626837833783620, 0.3137066458778873, 0.2223810344533745, 0.1012285362903763};
  std::vector<double> cuts{std::max(a0, -1.0), std::min(a1, 1.0)};
  for (double b : {b0, b1})
    if (std::abs(b) < 1) {
      const double k = std::sqrt(1 - b * b);
      for (double c : {-k, k})
        if (c > cuts[0] && c < cuts[1]) cuts.push_back(c);
    }
  std::sort(cuts.begin(), cuts.end());
  double total = 0;
  for (std::size_t p = 0; p + 1 < cuts.size(); ++p) {
    const double mid = 0.5 * (cuts[p] + cuts[p + 1]), half = 0.5 * (cuts[p + 1] - cuts[p]);
    const int panels = 400;  // in u = 0..pi
    for (int q = 0; q < panels; ++q) {
      const double u0 = pi * q / panels, du = pi / panels;
      for (int g = 0; g < 8; ++g) {
        const double u = u0 + 0.5 * du * (node[g] + 1);
        const double x = mid - half * std::cos(u), jac = half * std::sin(u);
        const double s = std::sqrt(std::max(0.0, 1 - x * x));
        total += 0.5 * du * weight[g] * jac * (segment_above(s, b0) - segment_above(s, b1));
      }
    }
  }
  return total;
}

TEST(LayerClippedSphere, InsideOutsideAndOnePlaneThroughCentre) {
  EXPECT_DOUBLE_EQ(sphere_volume_in_prism(xc, yc, r, -far, far, -far, far), whole);
  EXPECT_EQ(sphere_volume_in_prism(xc, yc, r, xc + r, far, -far, far), 0.0);
  EXPECT_NEAR(sphere_volume_in_prism(xc, yc, r, xc, far, -far, far), whole / 2, 1e-9 * whole / 2);
  EXPECT_NEAR(sphere_volume_in_prism(xc, yc, r, -far, far, -far, yc), whole / 2, 1e-9 * whole / 2);
}

TEST(LayerClippedSphere, PlaneAtDistanceGivesCap) {
  for (double a : {-0.9, -0.4, 0.0, 0.25, 0.6, 0.95, 0.999}) {
    const double v_right = sphere_volume_in_prism(xc, yc, r, xc + a * r, far, -far, far);
    const double v_below = sphere_volume_in_prism(xc, yc, r, -far, far, -far, yc - a * r);
    const double expected = cap(r - a * r);
    EXPECT_NEAR(v_right, expected, 1e-9 * expected) << "a = " << a;
    EXPECT_NEAR(v_below, expected, 1e-9 * expected) << "a = " << a;
  }
}

TEST(LayerClippedSphere, TwoPerpendicularPlanesThroughCentreGiveQuarter) {
  EXPECT_NEAR(sphere_volume_in_prism(xc, yc, r, xc, far, yc, far), whole / 4, 1e-9 * whole / 4);
  EXPECT_NEAR(sphere_volume_in_prism(xc, yc, r, -far, xc, yc, far), whole / 4, 1e-9 * whole / 4);
  EXPECT_NEAR(sphere_volume_in_prism(xc, yc, r, -far, xc, -far, yc), whole / 4, 1e-9 * whole / 4);
}

TEST(LayerClippedSphere, FourQuadrantsAroundAnyPointAddUpToTheSphere) {
  for (double px : {-0.7, -0.1, 0.3, 0.8})
    for (double py : {-0.5, 0.05, 0.45, 0.9}) {
      const double x = xc + px * r, y = yc + py * r;
      const double sum =
          sphere_volume_in_prism(xc, yc, r, -far, x, -far, y) + sphere_volume_in_prism(xc, yc, r, x, far, -far, y) +
          sphere_volume_in_prism(xc, yc, r, -far, x, y, far) + sphere_volume_in_prism(xc, yc, r, x, far, y, far);
      EXPECT_NEAR(sum, whole, 1e-12 * whole) << px << " " << py;
    }
}

TEST(LayerClippedSphere, SymmetricInItsTwoPlanes) {
  for (double a : {-0.6, 0.1, 0.5})
    for (double b : {-0.3, 0.2, 0.7})
      EXPECT_NEAR(unit_sphere_quadrant_volume(a, b), unit_sphere_quadrant_volume(b, a), 1e-13);
}

TEST(LayerClippedSphere, GeneralBoxMatchesIntegratedCircleSegments) {
  const double boxes[][4] = {{-0.2, 0.7, -0.5, 0.3}, {0.3, 0.9, 0.2, 0.8}, {-0.9, 0.1, 0.4, 0.95},
                             {-2, 0.5, -0.8, 2},     {0.05, 2, -2, -0.6},  {-0.99, 0.99, -0.99, 0.99}};
  for (const auto &b : boxes) {
    const double v = sphere_volume_in_prism(xc, yc, r, xc + b[0] * r, xc + b[1] * r, yc + b[2] * r, yc + b[3] * r);
    const double ref = numeric_box_volume(b[0], b[1], b[2], b[3]) * r * r * r;
    EXPECT_NEAR(v, ref, 1e-9 * ref) << b[0] << " " << b[1] << " " << b[2] << " " << b[3];
  }
}

}  // namespace
