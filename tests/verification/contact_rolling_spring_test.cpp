// The rolling spring (rolling_model: epsd) of every law against closed forms. A sphere rests on the
// floor under gravity, without sliding friction (so nothing but the rolling part resists its spin),
// and a torque T about y is applied. With k_n = m g / delta (the secant stiffness at rest, the one
// the laws give the spring) the spring is k_r = 2.25 k_n mu_r^2 r^2 and the sphere's spin obeys
// I theta'' = T - k_r theta - C_r theta' below the limit M_m = mu_r r m g, I = (2/5) m r^2:
//   - below the limit it turns to the elastic angle T / k_r and rests there (the torque balanced,
//     no spin left, nothing oscillating);
//   - undamped (rolling_damping 0) it swings between 0 and 2 T / k_r with period 2 pi sqrt(I / k_r);
//   - above the limit the spring holds M_m and the dashpot is off: it spins up at (T - M_m) / I.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "verification/contact_laws.hpp"
#include "verification/contact_support.hpp"

namespace sm = spreadmap;
using sm::test::Integrator;
using sm::test::V3;

namespace {

constexpr double g = 9.81, mu_r = 0.1;
const sm::test::Plane floor_plane{{0, 0, 0}, {0, 0, 1}};

// Each law with friction off, the rolling spring on, a strongly damped normal contact (so the sphere
// settles quickly), and `damping` as the rolling dashpot's eta_r.
template <class Law> Law spring_law(double damping) {
  nlohmann::json p = {{"friction", 0.0},           {"restitution", 0.1},         {"rolling_friction", mu_r},
                      {"rolling_model", "epsd"}, {"rolling_damping", damping}};
  if constexpr (std::is_same_v<Law, sm::HertzMindlin>) p["youngs_modulus"] = 1e8;
  return sm::test::bind_law<Law>(p);
}

// A sphere settled on the floor; then the torque T about y from t = 0, for `duration`. Records the
// angle turned, the largest angle and when it was reached. The angle integrates the spin at the half
// steps, where the law sees it (velocity Verlet: the full step's spin less the last half kick).
template <class Law> struct Spin {
  double k_r, limit, inertia;          // of the settled contact [N m/rad], [N m], [kg m^2]
  double angle = 0, peak = 0, t_peak = 0;
  double w_end = 0, torque_end = 0;    // spin [rad/s] and the contact's torque about y [N m]
  double t_end = 0;
  double w_max_late = 0;               // the largest |w_y| over the last fifth [rad/s]
  double w_early = 0, t_early = 0;     // spin at 20 % of the duration (spin-up)
};
template <class Law> Spin<Law> spin(double damping, double torque_of_limit, double duration) {
  sm::test::Sphere s = sm::test::study_sphere({0, 0, 125e-6});
  const double dt = 1e-7;
  Integrator<Law> run(spring_law<Law>(damping), {s}, dt, {0, 0, -g}, {floor_plane});
  while (run.time() < 2e-3) run.step();  // settles (restitution 0.1)
  const sm::test::Sphere &b = run.spheres()[0];
  Spin<Law> out;
  const double delta = run.wall_overlap(0);
  out.k_r = 2.25 * (b.m * g / delta) * mu_r * mu_r * b.r * b.r;
  out.limit = mu_r * b.r * b.m * g;
  out.inertia = b.inertia();
  run.sphere(0).w = {0, 0, 0};
  const double torque = torque_of_limit * out.limit;
  run.set_external_torque(0, {0, torque, 0});
  const double start = run.time();
  while (run.time() - start < duration) {
    run.step();
    const double t = run.time() - start, w = run.spheres()[0].w.y;
    out.angle += (w - (run.torque(0).y + torque) * 0.5 * dt / out.inertia) * dt;
    if (out.angle > out.peak) out.peak = out.angle, out.t_peak = t;
    if (t > 0.8 * duration) out.w_max_late = std::max(out.w_max_late, std::abs(w));
    if (out.t_early == 0 && t >= 0.2 * duration) out.w_early = w, out.t_early = t;
  }
  out.t_end = run.time() - start;
  out.w_end = run.spheres()[0].w.y;
  out.torque_end = run.torque(0).y;
  return out;
}

template <class Law> class RollingSpring : public ::testing::Test {};
TYPED_TEST_SUITE(RollingSpring, sm::test::ContactLaws::Types);

TYPED_TEST(RollingSpring, BelowTheLimitTheSphereTurnsToTheElasticAngleAndRests) {
  const double torque_of_limit = 0.4;
  const auto s = spin<TypeParam>(0.3, torque_of_limit, 4e-3);
  const double torque = torque_of_limit * s.limit, elastic = torque / s.k_r;
  EXPECT_NEAR(s.angle, elastic, 1e-7 * elastic) << "theta = T / k_r";
  EXPECT_NEAR(s.torque_end, -torque, 1e-9 * torque) << "the spring balances the torque";
  EXPECT_LT(s.w_max_late, 1e-6 * elastic * std::sqrt(s.k_r / s.inertia)) << "at rest: no spin left, no oscillation";
}

TYPED_TEST(RollingSpring, UndampedItSwingsToTwiceTheElasticAngleAtTheSpringsPeriod) {
  const double torque_of_limit = 0.4;
  const double omega = std::sqrt(spin<TypeParam>(0, torque_of_limit, 1e-9).k_r / spin<TypeParam>(0, 0, 1e-9).inertia);
  const auto s = spin<TypeParam>(0, torque_of_limit, 0.9 * 2 * sm::pi / omega);  // past the first peak only
  const double elastic = torque_of_limit * s.limit / s.k_r;
  EXPECT_NEAR(s.peak, 2 * elastic, 1e-5 * elastic) << "theta(t) = (T / k_r) (1 - cos omega t)";
  EXPECT_NEAR(s.t_peak, sm::pi / omega, 2e-3 * sm::pi / omega) << "omega = sqrt(k_r / I)";
}

TYPED_TEST(RollingSpring, AboveTheLimitItSpinsUpAgainstTheFullyMobilisedTorque) {
  const double torque_of_limit = 2;
  const auto s = spin<TypeParam>(0.3, torque_of_limit, 1e-3);
  const double alpha = (s.w_end - s.w_early) / (s.t_end - s.t_early), expected = (torque_of_limit - 1) * s.limit / s.inertia;
  EXPECT_NEAR(alpha, expected, 1e-9 * expected) << "(T - mu_r r m g) / I";
  EXPECT_NEAR(s.torque_end, -s.limit, 1e-12 * s.limit) << "the spring holds M_m = mu_r r |F_n|, no dashpot";
}

// The rolling part adds 3 values of history after the law's own, and nothing without the spring.
TYPED_TEST(RollingSpring, AddsItsThreeHistoryValuesOnlyWhenSelected) {
  EXPECT_EQ(sm::history_of(spring_law<TypeParam>(0.3)), TypeParam::history + 3);
  nlohmann::json constant = {{"rolling_friction", mu_r}};
  if constexpr (std::is_same_v<TypeParam, sm::HertzMindlin>) constant["youngs_modulus"] = 1e8;
  EXPECT_EQ(sm::history_of(sm::test::bind_law<TypeParam>(constant)), TypeParam::history);
}

}  // namespace
