// spreader/oscillating_roller: its rotation in closed form (angular velocity, angle, rest), its
// contacts' surface velocity, and the built module through its C descriptor as the host loads it.
#include <dlfcn.h>
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "plugins/spreader/oscillating_roller/oscillating_roller.hpp"

namespace sm = spreadmap;
using sm::spreader::OscillatingRoller;
using V = sm::Vec3<double>;

namespace {

constexpr double pi = 3.14159265358979323846;
// The schema's defaults: D = 10 mm, gap 0.5 mm, start 6 mm, travel 26 mm at U = 0.1 m/s (0.26 s).
constexpr double R = 5e-3, axis_z = 5.5e-3, start = 6e-3, U = 0.1, T = 0.26, r = 125e-6, delta = 10e-6;

nlohmann::json defaults() {
  nlohmann::json j;
  for (const auto &p : OscillatingRoller::params) j[p.name] = p.def;
  return j;
}

OscillatingRoller bind(double omega, double amplitude, double frequency) {
  auto j = defaults();
  j["omega"] = omega, j["amplitude"] = amplitude, j["frequency"] = frequency;
  return OscillatingRoller::bind(sm::Values(j));
}

sm::sm_spreader_pose_v2 pose_of(const OscillatingRoller &g, double t) {
  sm::sm_spreader_pose_v2 p{};
  g.pose(t, &p);
  return p;
}

// The contact of a sphere just under the roller's lowest point at time t (overlap delta).
sm::WallHit<double> under(const OscillatingRoller &g, double t) {
  sm::WallHit<double> hit{};
  EXPECT_TRUE(g(V{pose_of(g, t).reference[0], 0.0, axis_z - R - r + delta}, r, t, hit));
  return hit;
}

}  // namespace

TEST(OscillatingRoller, AngularVelocityIsTheMeanPlusTheOscillation) {
  const double omega = -20, A = 0.2, f = 40, k = 2 * pi * f;
  const auto g = bind(omega, A, f);
  for (double t : {0.0, 0.3 / f, 0.25 / f, 1.6 / f, 0.2}) {
    const double w = omega + A * k * std::sin(k * t);
    EXPECT_NEAR(pose_of(g, t).omega, w, 1e-12) << "t = " << t;
    // The lowest surface point moves at U - w R (U e_x + w e_y x (-R e_z)).
    EXPECT_NEAR(under(g, t).velocity.x, U - w * R, 1e-12) << "t = " << t;
    EXPECT_NEAR(under(g, t).overlap, delta, 1e-15);
  }
}

TEST(OscillatingRoller, AngleIsTheIntegralOfTheAngularVelocity) {
  const double omega = 15, A = 0.3, f = 25, k = 2 * pi * f;
  const auto g = bind(omega, A, f);
  for (double t : {0.01, 0.5 / f, 0.123, 0.25}) {
    EXPECT_NEAR(pose_of(g, t).angle, omega * t + A * (1 - std::cos(k * t)), 1e-12) << "t = " << t;
    // and its rate is the angular velocity (central difference, error ~ h^2 w''' / 6 < 1e-6)
    const double h = 1e-6, rate = (pose_of(g, t + h).angle - pose_of(g, t - h).angle) / (2 * h);
    EXPECT_NEAR(rate, pose_of(g, t).omega, 1e-5 * (std::abs(omega) + A * k));
  }
  // half a period on: the oscillation has added 2 A
  EXPECT_NEAR(pose_of(g, 0.5 / f).angle, omega * 0.5 / f + 2 * A, 1e-12);
}

TEST(OscillatingRoller, RestsBeforeTheStartAndAfterTheTravel) {
  const double omega = -20, A = 0.2, f = 40, k = 2 * pi * f;
  const auto g = bind(omega, A, f);
  for (double t : {-1.0, -1e-9}) {
    const auto p = pose_of(g, t);
    EXPECT_DOUBLE_EQ(p.reference[0], start);
    EXPECT_EQ(p.omega, 0.0);
    EXPECT_EQ(p.velocity[0], 0.0);
    EXPECT_EQ(p.angle, 0.0);
    EXPECT_EQ(under(g, t).velocity.x, 0.0);  // the heap settles beside a still surface
  }
  const auto parked = pose_of(g, T + 0.1);
  EXPECT_NEAR(parked.reference[0], start + U * T, 1e-15);
  EXPECT_EQ(parked.omega, 0.0);
  EXPECT_NEAR(parked.angle, omega * T + A * (1 - std::cos(k * T)), 1e-12);  // frozen where it stopped
  EXPECT_EQ(under(g, T + 0.1).velocity.x, 0.0);
}

TEST(OscillatingRoller, WithoutAmplitudeItTurnsSteadily) {
  const auto g = bind(12, 0, 40);
  EXPECT_NEAR(pose_of(g, 0.1).angle, 1.2, 1e-15);
  EXPECT_NEAR(under(g, 0.1).velocity.x, U - 12 * R, 1e-15);
  EXPECT_DOUBLE_EQ(g.max_surface_speed(), U + 12 * R);
}

TEST(OscillatingRoller, NoSurfacePointIsFasterThanItsBound) {
  const double omega = -20, A = 0.2, f = 40;
  const auto g = bind(omega, A, f);
  EXPECT_DOUBLE_EQ(g.max_surface_speed(), U + (20 + A * 2 * pi * f) * R);
  for (int i = 0; i <= 400; ++i) {
    const double t = T * i / 400;
    const auto v = under(g, t).velocity;
    EXPECT_LE(std::hypot(v.x, v.z), g.max_surface_speed() * (1 + 1e-12)) << "t = " << t;
  }
}

TEST(OscillatingRoller, ModuleDescribesItselfThroughTheAbi) {
  void *handle = dlopen(OSCILLATING_ROLLER_MODULE, RTLD_NOW | RTLD_LOCAL);
  ASSERT_NE(handle, nullptr) << dlerror();
  const auto entry = reinterpret_cast<sm_plugin_entry_v1>(dlsym(handle, "spreadmap_plugin_v1"));
  ASSERT_NE(entry, nullptr);
  const sm_plugin_v1 *d = entry();
  EXPECT_EQ(d->abi, SPREADMAP_PLUGIN_ABI);
  EXPECT_STREQ(d->kind, "spreader");
  EXPECT_STREQ(d->name, "oscillating_roller");
  auto values = defaults();
  values["amplitude"] = 0.2;
  sm_error err{};
  void *self = d->create(values.dump().c_str(), &err);
  ASSERT_NE(self, nullptr) << err.text;
  const auto *ops = static_cast<const sm::sm_spreader_ops_v2 *>(d->ops);
  sm::sm_spreader_description_v2 description{};
  ops->describe(self, &description);
  EXPECT_NEAR(description.duration, T, 1e-15);
  EXPECT_DOUBLE_EQ(description.start, start);
  EXPECT_NEAR(description.end, start + U * T, 1e-15);
  EXPECT_DOUBLE_EQ(description.speed, U);
  EXPECT_NEAR(description.gap, axis_z - R, 1e-18);
  EXPECT_EQ(description.turns, 1);
  ASSERT_GT(description.vertices, 3u);
  for (std::uint32_t k = 0; k < description.vertices; ++k)
    EXPECT_NEAR(std::hypot(description.x[k], description.z[k]), R, 1e-15);
  // at rest, a sphere 1 um short of the lowest point does not touch; 1 um into it does
  const double below[3] = {start, 0.0, axis_z - R - r - 1e-6}, into[3] = {start, 0.0, axis_z - R - r + 1e-6};
  EXPECT_EQ(ops->touches(self, -1.0, below, r), 0);
  EXPECT_EQ(ops->touches(self, -1.0, into, r), 1);
  d->destroy(self);
}
