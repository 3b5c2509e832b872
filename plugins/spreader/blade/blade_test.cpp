// spreader/blade: overlap and normal on the flat faces, the flat bottom and the rounded or sharp
// lower corners, against closed forms.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "plugins/spreader/blade/blade.hpp"
#include "unit/spreader_values.hpp"

namespace sm = spreadmap;
using sm::spreader::Blade;
using V = sm::Vec3<double>;

namespace {

// thickness 1 mm (faces at x = 5.5 and 6.5 mm at t = 0), gap 0.5 mm, height 10 mm, U = 0.1 m/s.
constexpr double xc = 6e-3, half_t = 0.5e-3, gap = 0.5e-3, r = 125e-6, delta = 10e-6, U = 0.1;
constexpr double tol_len = 1e-15;

sm::WallHit<double> touch(const Blade &g, V p, double t = 0.0) {
  sm::WallHit<double> hit{0, {0, 0, 0}, {0, 0, 0}};
  EXPECT_TRUE(g(p, r, t, hit)) << "expected a contact at (" << p.x << ", " << p.y << ", " << p.z << ")";
  return hit;
}

void expect_normal(const sm::WallHit<double> &hit, double nx, double nz, double tol = 1e-12) {
  EXPECT_NEAR(hit.normal.x, nx, tol);
  EXPECT_NEAR(hit.normal.y, 0.0, tol);
  EXPECT_NEAR(hit.normal.z, nz, tol);
}

}  // namespace

TEST(SpreaderBlade, FlatFacesFrontAndBack) {
  const Blade g = sm::test::bind_with<Blade>({{"edge_radius", 0.2e-3}});
  const auto front = touch(g, {xc + half_t + r - delta, 0.0, 3e-3});
  EXPECT_NEAR(front.overlap, delta, tol_len);
  expect_normal(front, 1.0, 0.0);
  EXPECT_DOUBLE_EQ(front.velocity.x, U);
  EXPECT_DOUBLE_EQ(front.velocity.z, 0.0);
  const auto back = touch(g, {xc - half_t - r + delta, 0.0, 3e-3});
  EXPECT_NEAR(back.overlap, delta, tol_len);
  expect_normal(back, -1.0, 0.0);
}

TEST(SpreaderBlade, FlatBottomFace) {
  // With edge_radius 0.2 mm the bottom is flat for |x - xc| <= 0.3 mm.
  const Blade g = sm::test::bind_with<Blade>({{"edge_radius", 0.2e-3}});
  for (double u : {0.0, 0.25e-3, -0.25e-3}) {
    const auto hit = touch(g, {xc + u, 0.0, gap - r + delta});
    EXPECT_NEAR(hit.overlap, delta, tol_len);
    expect_normal(hit, 0.0, -1.0);
  }
}

TEST(SpreaderBlade, RoundedCornerActsLikeACylinderOfEdgeRadius) {
  // Arc centre of the front corner at (xc + t/2 - rho, gap + rho); a sphere at angle a below the
  // horizontal, at distance rho + r - delta from it: overlap delta, normal (cos a, 0, -sin a).
  const double rho = 0.2e-3, ax = xc + half_t - rho, az = gap + rho;
  const Blade g = sm::test::bind_with<Blade>({{"edge_radius", rho}});
  for (double deg : {10.0, 45.0, 80.0}) {
    const double a = deg * sm::pi / 180.0, c = rho + r - delta;
    const auto hit = touch(g, {ax + c * std::cos(a), 0.0, az - c * std::sin(a)});
    EXPECT_NEAR(hit.overlap, delta, 1e-14) << deg;
    expect_normal(hit, std::cos(a), -std::sin(a));
  }
  // Back corner, mirrored.
  const double c = rho + r - delta, s = std::sqrt(0.5);
  const auto back = touch(g, {xc - half_t + rho - c * s, 0.0, az - c * s});
  EXPECT_NEAR(back.overlap, delta, 1e-14);
  expect_normal(back, -s, -s);
}

TEST(SpreaderBlade, SharpCornerIsTheDistanceToTheCornerPoint) {
  const Blade g = sm::test::bind_with<Blade>({});  // edge_radius 0: sharp
  const double a = 30.0 * sm::pi / 180.0, c = r - delta;
  const auto hit = touch(g, {xc + half_t + c * std::cos(a), 0.0, gap - c * std::sin(a)});
  EXPECT_NEAR(hit.overlap, delta, 1e-14);
  expect_normal(hit, std::cos(a), -std::sin(a));
  // Just outside the corner's reach: no contact.
  sm::WallHit<double> none{};
  EXPECT_FALSE(g(V{xc + half_t + (r + 1e-9) * std::cos(a), 0.0, gap - (r + 1e-9) * std::sin(a)}, r, 0.0, none));
}

TEST(SpreaderBlade, CentreInsideUsesTheNearestFace) {
  // 0.1 mm inside the front face, 4 mm up: least penetration through the front face.
  const Blade g = sm::test::bind_with<Blade>({});
  const auto hit = touch(g, {xc + half_t - 0.1e-3, 0.0, 4e-3});
  EXPECT_NEAR(hit.overlap, r + 0.1e-3, 1e-15);
  expect_normal(hit, 1.0, 0.0);
}

TEST(SpreaderBlade, MovesAndParksAndRefusesOversizedEdge) {
  const Blade g = sm::test::bind_with<Blade>({{"travel", 10e-3}, {"edge_radius", 0.5e-3}});
  EXPECT_DOUBLE_EQ(sm::test::description_of(g).duration, 0.1);
  EXPECT_DOUBLE_EQ(g.max_surface_speed(), U);
  const auto hit = touch(g, {xc + U * 0.05 + half_t + r - delta, 0.0, 3e-3}, 0.05);
  EXPECT_NEAR(hit.overlap, delta, 1e-14);
  auto pose = sm::test::pose_of(g, 0.05);
  EXPECT_NEAR(pose.reference[0], xc + U * 0.05, 1e-15);
  EXPECT_DOUBLE_EQ(pose.reference[2], gap);
  EXPECT_DOUBLE_EQ(pose.x_max - pose.x_min, 2 * half_t);
  EXPECT_DOUBLE_EQ(pose.angle, 0.0);
  pose = sm::test::pose_of(g, 1.0);
  EXPECT_NEAR(pose.reference[0], xc + 10e-3, 1e-15);
  EXPECT_DOUBLE_EQ(pose.velocity[0], 0.0);
  EXPECT_THROW(sm::test::bind_with<Blade>({{"edge_radius", 0.6e-3}}), sm::ParamError);  // > thickness / 2
}

// The outline is the rounded rectangle: its extent is the blade's, its lower corners lie on the
// edge arcs, and its lowest points are at the reference (the middle of the lowest edge).
TEST(SpreaderBlade, OutlineIsTheRoundedRectangle) {
  const Blade g = sm::test::bind_with<Blade>({{"edge_radius", 0.25e-3}});
  const auto d = sm::test::description_of(g);
  double x_lo = 1, x_hi = -1, z_lo = 1, z_hi = -1;
  for (std::uint32_t k = 0; k < d.vertices; ++k) {
    x_lo = std::min(x_lo, d.x[k]), x_hi = std::max(x_hi, d.x[k]);
    z_lo = std::min(z_lo, d.z[k]), z_hi = std::max(z_hi, d.z[k]);
    if (d.z[k] < 0.25e-3 && std::abs(d.x[k]) > half_t - 0.25e-3) {  // on an arc: 0.25 mm from its centre
      EXPECT_NEAR(std::hypot(std::abs(d.x[k]) - (half_t - 0.25e-3), d.z[k] - 0.25e-3), 0.25e-3, 1e-15);
    }
  }
  EXPECT_NEAR(x_lo, -half_t, 1e-15);
  EXPECT_NEAR(x_hi, half_t, 1e-15);
  EXPECT_NEAR(z_lo, 0.0, 1e-15);
  EXPECT_DOUBLE_EQ(d.gap, gap);
  EXPECT_EQ(d.turns, 0);
}
