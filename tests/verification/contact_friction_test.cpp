// contact/hooke_slider's tangential side against closed forms: a sphere on an incline (rolling below
// the slip limit tan(theta) < (7/2) mu, sliding above), oblique impacts on a wall (gross sliding with
// the friction impulse that |F_n| makes available; rolling off at 5/7 of the tangential speed) and
// rolling resistance. The incline is the wall z = 0 with gravity tilted by theta (the same physics).
#include "plugins/contact/hooke_slider/hooke_slider.hpp"
#include "verification/contact_support.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace sm = spreadmap;
using sm::test::Integrator;
using sm::test::Sphere;
using sm::test::V3;
using json = nlohmann::json;

namespace {

constexpr double g = 9.81, mu = 0.185, omega0 = 0.5 / 2.5e-6;
const double radius = sm::test::study_sphere().r;
const sm::test::Plane floor_plane{{0, 0, 0}, {0, 0, 1}};

// A sphere resting (at its equilibrium overlap) on the floor under gravity tilted by theta, with an
// initial velocity along x and spin about y. Returns the integrator after `duration`, and the
// velocity and spin at `t_mark` through the out-parameters.
struct Slope {
  V3 v_mark, w_mark, v_end, w_end;
  double t_mark, t_end;
};
Slope on_slope(const sm::HookeSlider &law, double theta, double v0, double duration, double t_mark) {
  const V3 gravity{g * std::sin(theta), 0, -g * std::cos(theta)};
  const double rest = g * std::cos(theta) / (omega0 * omega0);  // m g cos / K_n with K_n = m omega0^2
  Sphere s = sm::test::study_sphere({0, 0, radius - rest}, {v0, 0, 0}, {0, v0 / radius, 0});
  Integrator<sm::HookeSlider> run(law, {s}, sm::pi / omega0 / 50, gravity, {floor_plane});
  Slope out{};
  while (run.time() < duration) {
    run.step();
    if (out.t_mark == 0 && run.time() >= t_mark) {
      out.t_mark = run.time();
      out.v_mark = run.spheres()[0].v;
      out.w_mark = run.spheres()[0].w;
    }
  }
  out.t_end = run.time();
  out.v_end = run.spheres()[0].v;
  out.w_end = run.spheres()[0].w;
  return out;
}

class Incline : public ::testing::TestWithParam<std::string> {};  // the slider variant

TEST_P(Incline, BelowTheSlipLimitItRollsAtFiveSeventhsGSinTheta) {
  const double theta = 20 * sm::pi / 180;
  ASSERT_LT(std::tan(theta), 3.5 * mu);
  const Slope s = on_slope(sm::test::bind_law<sm::HookeSlider>({{"slider", GetParam()}}), theta, 0, 2e-3, 0.5e-3);
  const double a = (s.v_end.x - s.v_mark.x) / (s.t_end - s.t_mark), expected = 5.0 / 7.0 * g * std::sin(theta);
  EXPECT_NEAR(a, expected, 0.01 * expected);
  EXPECT_NEAR(radius * s.w_end.y, s.v_end.x, 0.01 * s.v_end.x) << "rolling: v = r w";
}

TEST_P(Incline, AboveTheSlipLimitItSlidesAndSpinsUp) {
  const double theta = 45 * sm::pi / 180;
  ASSERT_GT(std::tan(theta), 3.5 * mu);
  const Slope s = on_slope(sm::test::bind_law<sm::HookeSlider>({{"slider", GetParam()}}), theta, 0, 2e-3, 0.5e-3);
  const double span = s.t_end - s.t_mark;
  const double a = (s.v_end.x - s.v_mark.x) / span, expected = g * (std::sin(theta) - mu * std::cos(theta));
  EXPECT_NEAR(a, expected, 0.01 * expected);
  const double alpha = (s.w_end.y - s.w_mark.y) / span, spin = 2.5 * mu * g * std::cos(theta) / radius;
  EXPECT_NEAR(alpha, spin, 0.01 * spin) << "(5/2) mu g cos(theta) / r";
}
INSTANTIATE_TEST_SUITE_P(Slider, Incline,
                         ::testing::Values(std::string("stick"), std::string("viscous"), std::string("coulomb")),
                         [](const ::testing::TestParamInfo<std::string> &info) { return info.param; });

// An oblique impact on the floor at v_n = 0.5 m/s with tangential speed v_t and no spin, no gravity.
struct Bounce {
  double dv_t, r_dw;  // change of tangential velocity and of r w_y
  V3 v, w;
};
Bounce oblique(const sm::HookeSlider &law, double v_t) {
  Integrator<sm::HookeSlider> run(law, {sm::test::study_sphere({0, 0, radius}, {v_t, 0, -0.5})}, sm::pi / omega0 / 1000,
                                  {0, 0, 0}, {floor_plane});
  bool touched = false;
  for (int k = 0; k < 100000; ++k) {
    run.step();
    touched = touched || run.wall_overlap(0) > 0;
    if (touched && run.wall_overlap(0) <= 0) break;
  }
  const Sphere &s = run.spheres()[0];
  return {s.v.x - v_t, radius * s.w.y, s.v, s.w};
}

struct Case {
  double eps;
  bool clamp;
};
class GrossSliding : public ::testing::TestWithParam<Case> {};

TEST_P(GrossSliding, TangentialImpulseIsMuTimesTheIntegralOfAbsoluteNormalForce) {
  const auto [eps, clamp] = GetParam();
  const double e_c = sm::clamped_restitution(sm::damping_ratio_from_restitution(eps));
  // integral of |F_n| over the impact / (m v_n): unclamped the attractive tail counts too
  const double factor = clamp ? 1 + e_c : 1 + 2 * e_c - eps;
  const double v_t = 2.0;
  ASSERT_GT(v_t, 3.5 * mu * 0.5 * factor) << "slip must survive the whole impact";
  const Bounce b = oblique(sm::test::bind_law<sm::HookeSlider>({{"restitution", eps}, {"clamp_normal", clamp}}), v_t);
  const double expected = -mu * 0.5 * factor;
  EXPECT_NEAR(b.dv_t, expected, 0.01 * std::abs(expected));
  EXPECT_NEAR(b.r_dw, -2.5 * b.dv_t, 0.01 * std::abs(2.5 * b.dv_t))
      << "r dw = (5/2) |dv_t|: torque of the same impulse";
}
INSTANTIATE_TEST_SUITE_P(Restitution, GrossSliding,
                         ::testing::Values(Case{0.8, false}, Case{0.5, false}, Case{0.8, true}, Case{0.5, true}),
                         [](const ::testing::TestParamInfo<Case> &info) {
                           return "eps" + std::to_string(int(std::lround(info.param.eps * 10))) +
                                  (info.param.clamp ? "_clamped" : "_unclamped");
                         });

TEST(RollingOff, TheSphereLeavesWithFiveSeventhsOfItsTangentialSpeed) {
  const double v_t = 0.1;  // sticks early: (7/2) mu v_n (1 + 2 e_c - eps) = 0.59 m/s of slip could be removed
  const Bounce b = oblique(sm::test::bind_law<sm::HookeSlider>(), v_t);
  EXPECT_NEAR(b.v.x, 5.0 / 7.0 * v_t, 0.01 * 5.0 / 7.0 * v_t);
  EXPECT_NEAR(b.v.x - radius * b.w.y, 0.0, 0.01 * v_t) << "no slip at exit";
}

// Rolling resistance (constant directional torque): rolling on the flat floor decelerates at
// (5/7) mu_r g (torque balance about the contact point with the rolling constraint), then stops and
// stays stopped; on a slope with tan(theta) < mu_r the sphere is held, creeping only at the steady speed
// of the two regularisations: 5 g sin(theta) dt of rolling (the torque limit I_r w / (2 dt) = r m g sin)
// plus 7 g sin(theta) dt of slip (the stick slider's m_t u / (2 dt) = m g sin).
TEST(RollingResistance, DeceleratesAtFiveSeventhsMuRGThenStops) {
  const double mu_r = 0.1;
  const auto law = sm::test::bind_law<sm::HookeSlider>({{"rolling_friction", mu_r}});
  const Slope rolling = on_slope(law, 0, 0.05, 2e-3, 0.5e-3);
  const double a = (rolling.v_end.x - rolling.v_mark.x) / (rolling.t_end - rolling.t_mark);
  EXPECT_NEAR(a, -5.0 / 7.0 * mu_r * g, 0.01 * 5.0 / 7.0 * mu_r * g);
  const Slope stopping = on_slope(law, 0, 3e-4, 2e-3, 1e-3);  // would stop after 0.43 ms
  EXPECT_LT(std::abs(stopping.v_end.x), 1e-9);
  EXPECT_LT(std::abs(radius * stopping.w_end.y), 1e-9);
}

TEST(RollingResistance, HoldsTheSphereOnASlopeFlatterThanMuR) {
  const double mu_r = 0.1, theta = std::atan(0.5 * mu_r), dt = sm::pi / omega0 / 50;
  const Slope s = on_slope(sm::test::bind_law<sm::HookeSlider>({{"rolling_friction", mu_r}}), theta, 0, 2e-3, 1e-3);
  const double creep = 12 * g * std::sin(theta) * dt;  // 1.8e-6 m/s; free rolling would reach 7e-4 m/s
  EXPECT_NEAR(s.v_end.x, creep, 0.01 * creep);
  EXPECT_NEAR(s.v_end.x, s.v_mark.x, 1e-3 * creep) << "steady: held, not accelerating";
}

}  // namespace
