// spreader/roller: overlap, normal and surface velocity against closed forms, the omega sign
// convention of paper-notes.md, the end faces, and the travel in time.
#include <gtest/gtest.h>

#include <cmath>

#include "plugins/spreader/roller/roller.hpp"
#include "unit/spreader_values.hpp"

namespace sm = spreadmap;
using sm::spreader::Roller;
using V = sm::Vec3<double>;

namespace {

// Defaults: D = 10 mm (R = 5 mm), gap 0.5 mm (axis at z = 5.5 mm), U = 0.1 m/s, start 6 mm.
constexpr double R = 5e-3, axis_z = 5.5e-3, start = 6e-3, U = 0.1, r = 125e-6, delta = 10e-6;
// Geometric quantities are sums of a few mm-sized doubles: 1e-15 m is ~100 ulp of them.
constexpr double tol_len = 1e-15, tol_vel = 1e-14;

Roller roller(double omega) { return sm::test::bind_with<Roller>({{"omega", omega}}); }

sm::WallHit<double> touch(const Roller &g, V p, double t = 0.0, double radius = r) {
  sm::WallHit<double> hit{0, {0, 0, 0}, {0, 0, 0}};
  EXPECT_TRUE(g(p, radius, t, hit)) << "expected a contact at (" << p.x << ", " << p.y << ", " << p.z << ")";
  return hit;
}

}  // namespace

TEST(SpreaderRoller, SphereUnderTheRollerBottomVelocityIsUMinusOmegaR) {
  // Centre straight below the axis, overlapping by delta: normal -z, contact point at the bottom,
  // whose velocity is (U - omega R) e_x: zero when rolling (omega = U/R), 2U at omega = -U/R.
  for (double omega : {0.0, 10.0, U / R, -U / R, 15.0, -15.0}) {
    const auto hit = touch(roller(omega), {start, 0.0, axis_z - R - r + delta});
    EXPECT_NEAR(hit.overlap, delta, tol_len);
    EXPECT_NEAR(hit.normal.x, 0.0, 1e-15);
    EXPECT_NEAR(hit.normal.z, -1.0, 1e-15);
    EXPECT_NEAR(hit.velocity.x, U - omega * R, tol_vel) << "omega = " << omega;
    EXPECT_NEAR(hit.velocity.z, 0.0, tol_vel);
  }
  EXPECT_NEAR(touch(roller(U / R), {start, 0.0, axis_z - R - r + delta}).velocity.x, 0.0, tol_vel);
  EXPECT_NEAR(touch(roller(-U / R), {start, 0.0, axis_z - R - r + delta}).velocity.x, 2 * U, tol_vel);
}

TEST(SpreaderRoller, SphereAheadAndBelowGetsRigidBodySurfaceVelocity) {
  // Front-lower quadrant at 45 degrees: n = (1, 0, -1)/sqrt2, contact arm R n, so
  // v = U e_x + omega e_y x (R n) = (U - omega R/sqrt2, 0, -omega R/sqrt2). Rolling forward
  // (omega > 0) the front surface moves down; counter-rotating it moves up.
  const double s = std::sqrt(0.5);
  for (double omega : {0.0, 20.0, -20.0}) {
    const double c = R + r - delta;
    const auto hit = touch(roller(omega), {start + c * s, 1e-3, axis_z - c * s});
    EXPECT_NEAR(hit.overlap, delta, tol_len);
    EXPECT_NEAR(hit.normal.x, s, 1e-14);
    EXPECT_NEAR(hit.normal.y, 0.0, 0.0);
    EXPECT_NEAR(hit.normal.z, -s, 1e-14);
    EXPECT_NEAR(hit.velocity.x, U - omega * R * s, tol_vel);
    EXPECT_NEAR(hit.velocity.z, -omega * R * s, tol_vel);
  }
  // Straight ahead at axis height: v = (U, 0, -omega R).
  const auto ahead = touch(roller(20.0), {start + R + r - delta, 0.0, axis_z});
  EXPECT_NEAR(ahead.velocity.x, U, tol_vel);
  EXPECT_NEAR(ahead.velocity.z, -20.0 * R, tol_vel);
}

TEST(SpreaderRoller, VelocityMatchesRigidBodyFormulaAllAround) {
  // Every direction around the axis: v = U e_x + (omega e_y) x (p_contact - c), |n| = 1.
  const Roller g = roller(-17.0);
  for (int k = 0; k < 72; ++k) {
    const double a = 2 * sm::pi * k / 72.0, c = R + r - delta;
    const V centre{start + c * std::cos(a), 2e-3, axis_z + c * std::sin(a)};
    const auto hit = touch(g, centre);
    EXPECT_NEAR(hit.overlap, delta, 1e-14);
    EXPECT_NEAR(sm::norm(hit.normal), 1.0, 1e-14);
    const V contact = centre - hit.normal * (r - hit.overlap);
    const V expected = V{U, 0, 0} + sm::cross(V{0, -17.0, 0}, contact - V{start, 2e-3, axis_z});
    EXPECT_NEAR(hit.velocity.x, expected.x, tol_vel);
    EXPECT_NEAR(hit.velocity.y, expected.y, tol_vel);
    EXPECT_NEAR(hit.velocity.z, expected.z, tol_vel);
  }
}

TEST(SpreaderRoller, NoContactWhenApartOrJustTouching) {
  const Roller g = roller(0.0);
  sm::WallHit<double> hit{};
  EXPECT_FALSE(g(V{start, 0.0, axis_z - R - r - 1e-9}, r, 0.0, hit));
  EXPECT_FALSE(g(V{start + 20e-3, 0.0, 1e-3}, r, 0.0, hit));
}

TEST(SpreaderRoller, EndFacesBoundTheLength) {
  // length 70 mm centred on y_centre = 10 mm: ends at y = -25 mm and 45 mm.
  const Roller g = sm::test::bind_with<Roller>({{"y_centre", 10e-3}});
  const double end = 45e-3, below = axis_z - R - r + delta;
  sm::WallHit<double> hit{};
  EXPECT_TRUE(g(V{start, end - 1e-6, below}, r, 0.0, hit));          // inside the length: radial contact
  EXPECT_FALSE(g(V{start, end + r + 1e-6, below}, r, 0.0, hit));     // beyond the length: none
  EXPECT_FALSE(g(V{start, -25e-3 - r - 1e-6, below}, r, 0.0, hit));  // beyond the other end: none
  // Centre inside the cylinder's radius, half a radius beyond the end: end-face contact along +y.
  const auto face = touch(g, {start, end + 0.5 * r, axis_z - 1e-3});
  EXPECT_NEAR(face.overlap, 0.5 * r, tol_len);
  EXPECT_NEAR(face.normal.y, 1.0, 0.0);
  // Beyond the rim both radially (30 um) and axially (40 um): distance 50 um, normal (0.6 e_r, 0.8 e_y).
  const auto rim = touch(g, {start, end + 40e-6, axis_z - R - 30e-6});
  EXPECT_NEAR(rim.overlap, r - 50e-6, 1e-14);
  EXPECT_NEAR(rim.normal.y, 0.8, 1e-9);
  EXPECT_NEAR(rim.normal.z, -0.6, 1e-9);
}

TEST(SpreaderRoller, TravelsAtUThenStops) {
  const Roller g = sm::test::bind_with<Roller>({{"omega", 12.0}, {"travel", 20e-3}});
  const auto d = sm::test::description_of(g);
  EXPECT_DOUBLE_EQ(d.duration, 0.2);  // 20 mm at 0.1 m/s
  EXPECT_DOUBLE_EQ(d.start, start);
  EXPECT_DOUBLE_EQ(d.end, start + 20e-3);
  EXPECT_DOUBLE_EQ(d.speed, U);
  EXPECT_DOUBLE_EQ(d.gap, axis_z - R);
  EXPECT_EQ(d.turns, 1);
  EXPECT_DOUBLE_EQ(g.max_surface_speed(), U + 12.0 * R);
  auto pose = sm::test::pose_of(g, 0.05);
  EXPECT_NEAR(pose.reference[0], start + U * 0.05, 1e-15);
  EXPECT_DOUBLE_EQ(pose.reference[2], axis_z);
  EXPECT_DOUBLE_EQ(pose.angle, 12.0 * 0.05);
  EXPECT_DOUBLE_EQ(pose.velocity[0], U);
  EXPECT_DOUBLE_EQ(pose.x_min, pose.reference[0] - R);
  pose = sm::test::pose_of(g, 0.5);  // after the end: parked, still
  EXPECT_NEAR(pose.reference[0], start + 20e-3, 1e-15);
  EXPECT_DOUBLE_EQ(pose.angle, 12.0 * 0.2);
  EXPECT_DOUBLE_EQ(pose.velocity[0], 0.0);
  EXPECT_DOUBLE_EQ(pose.omega, 0.0);
  pose = sm::test::pose_of(g, -1.0);  // before the start: at rest at start
  EXPECT_DOUBLE_EQ(pose.reference[0], start);
  EXPECT_DOUBLE_EQ(pose.velocity[0], 0.0);
  EXPECT_DOUBLE_EQ(pose.omega, 0.0);
  // The contact follows the pose; a parked roller's surface is at rest.
  const auto moving = touch(g, {start + U * 0.05, 0.0, axis_z - R - r + delta}, 0.05);
  EXPECT_NEAR(moving.velocity.x, U - 12.0 * R, tol_vel);
  const auto parked = touch(g, {start + 20e-3, 0.0, axis_z - R - r + delta}, 0.5);
  EXPECT_NEAR(parked.overlap, delta, tol_len);
  EXPECT_DOUBLE_EQ(parked.velocity.x, 0.0);
  const auto resting = touch(g, {start, 0.0, axis_z - R - r + delta}, -1.0);  // before the start: still
  EXPECT_NEAR(resting.overlap, delta, tol_len);
  EXPECT_DOUBLE_EQ(resting.velocity.x, 0.0);
}

TEST(SpreaderRoller, EndOverridesTravel) {
  const Roller g = sm::test::bind_with<Roller>({{"end", 32e-3}, {"U", 0.05}});
  EXPECT_NEAR(sm::test::description_of(g).duration, 26e-3 / 0.05, 1e-15);
  EXPECT_THROW(sm::test::bind_with<Roller>({{"end", 5e-3}}), sm::ParamError);  // behind start = 6 mm
}

TEST(SpreaderRoller, SinglePrecisionAgrees) {
  const Roller g = roller(-20.0);
  const double s = std::sqrt(0.5), c = R + r - delta;
  sm::WallHit<float> hf{};
  ASSERT_TRUE(g(sm::Vec3<float>{float(start + c * s), 0.f, float(axis_z - c * s)}, float(r), 0.f, hf));
  const auto hd = touch(g, {start + c * s, 0.0, axis_z - c * s});
  // float positions carry ~6e-3 m * 6e-8 = 4e-10 m of rounding; the overlap inherits it.
  EXPECT_NEAR(hf.overlap, hd.overlap, 2e-9);
  EXPECT_NEAR(hf.velocity.x, hd.velocity.x, 1e-6);
  EXPECT_NEAR(hf.velocity.z, hd.velocity.z, 1e-6);
}

// The outline the figures draw is the disc about the axis: every vertex at R from the reference.
TEST(SpreaderRoller, OutlineIsTheDiscAboutItsAxis) {
  const auto d = sm::test::description_of(sm::test::bind_with<Roller>());
  ASSERT_GE(d.vertices, 36u);
  for (std::uint32_t k = 0; k < d.vertices; ++k) EXPECT_NEAR(std::hypot(d.x[k], d.z[k]), R, 1e-15);
}
