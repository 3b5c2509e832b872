// Closed-form checks of the shared contact pieces (contact_parts.hpp) and of what each law reports
// to the host for its time step (natural_frequency, damping_ratio).
#include <spreadmap/contact_parts.hpp>

#include "plugins/contact/hertz_mindlin/hertz_mindlin.hpp"
#include "plugins/contact/hooke_history/hooke_history.hpp"
#include "plugins/contact/hooke_slider/hooke_slider.hpp"
#include "verification/contact_support.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace sm = spreadmap;
using sm::test::V3;

namespace {

// Unclamped linear spring-dashpot: rebound = exp(-pi zeta / sqrt(1 - zeta^2)).
double unclamped_restitution(double zeta) { return std::exp(-sm::pi * zeta / std::sqrt(1 - zeta * zeta)); }

TEST(ContactParts, DampingRatioInvertsTheUnclampedRestitutionWithExactLimits) {
  EXPECT_EQ(sm::damping_ratio_from_restitution(1.0), 0.0);
  EXPECT_FALSE(std::signbit(sm::damping_ratio_from_restitution(1.0))) << "+0, not -0";
  EXPECT_EQ(sm::damping_ratio_from_restitution(0.0), 1.0);
  const double l = std::log(1e-300);  // eps -> 0 tends to critical damping as 1 - pi^2 / (2 ln^2 eps)
  EXPECT_NEAR(sm::damping_ratio_from_restitution(1e-300), 1 - sm::pi * sm::pi / (2 * l * l), 1e-9);
  EXPECT_NEAR(sm::damping_ratio_from_restitution(0.8), 0.070850, 5e-7) << "the LIGGGHTS peer runs' value";
  for (double eps : {0.99, 0.8, 0.5, 0.1, 1e-3})
    EXPECT_NEAR(unclamped_restitution(sm::damping_ratio_from_restitution(eps)), eps, 1e-14 * (1 + eps)) << eps;
}

TEST(ContactParts, ClampedRestitutionClosedForm) {
  EXPECT_EQ(sm::clamped_restitution(0.0), 1.0);
  EXPECT_DOUBLE_EQ(sm::clamped_restitution(1.0), std::exp(-2.0));
  // continuous across critical damping, from both sides
  EXPECT_NEAR(sm::clamped_restitution(1 - 1e-7), std::exp(-2.0), 1e-6);
  EXPECT_NEAR(sm::clamped_restitution(1 + 1e-7), std::exp(-2.0), 1e-6);
  // clamping never lowers the restitution, and it never falls below e^-2 for eps in (0, 1]
  for (double eps : {0.95, 0.8, 0.5, 0.2, 0.05, 1e-6}) {
    const double ec = sm::clamped_restitution(sm::damping_ratio_from_restitution(eps));
    EXPECT_GE(ec, eps) << eps;
    EXPECT_GE(ec, std::exp(-2.0) - 1e-15) << eps;
  }
  // eps = 0.8: the numbers the oblique-impact closed forms use
  EXPECT_NEAR(sm::clamped_restitution(sm::damping_ratio_from_restitution(0.8)), 0.808099, 1e-6);
}

TEST(ContactParts, ClampCorrectionInvertsTheClampedRestitution) {
  EXPECT_EQ(sm::damping_ratio_for_clamped_restitution(1.0), 0.0);
  for (double eps : {0.9, 0.8, 0.5, std::exp(-2.0), 0.1, 0.01, 1e-4}) {
    const double zeta = sm::damping_ratio_for_clamped_restitution(eps);
    EXPECT_NEAR(sm::clamped_restitution(zeta), eps, 1e-12) << eps;
  }
  EXPECT_GT(sm::damping_ratio_for_clamped_restitution(0.1), 1.0) << "below e^-2 the clamped dashpot is overdamped";
  EXPECT_THROW(sm::damping_ratio_for_clamped_restitution(0.0), sm::ParamError);
}

TEST(ContactParts, StickSliderRemovesHalfTheSlipBelowTheCap) {
  const double m_eq = 2e-8, dt = 1e-7, cap = 1e-3;
  const V3 slow{1e-6, 0, 0}, fast{0, 2, 0};
  const V3 f = sm::slider_force(sm::Slider::stick, cap, slow, m_eq, dt, 0.0, 0.0);
  // impulse f dt over the tangential mass (2/7) m_eq changes the slip by exactly half of it
  EXPECT_NEAR(f.x * dt / (2.0 / 7.0 * m_eq), -0.5e-6, 1e-20);
  EXPECT_EQ(f.y, 0.0);
  const V3 g = sm::slider_force(sm::Slider::stick, cap, fast, m_eq, dt, 0.0, 0.0);
  EXPECT_DOUBLE_EQ(g.y, -cap);
  const V3 zero = sm::slider_force(sm::Slider::stick, cap, V3{0, 0, 0}, m_eq, dt, 0.0, 0.0);
  EXPECT_EQ(sm::norm(zero), 0.0);
}

TEST(ContactParts, ViscousAndCoulombSliders) {
  const double m_eq = 2e-8, dt = 1e-7, cap = 1e-4, gamma = 28340.1;
  const V3 slow{0, 0, 1e-5}, fast{0, 0, 1};
  EXPECT_DOUBLE_EQ(sm::slider_force(sm::Slider::viscous, cap, slow, m_eq, dt, gamma, 0.0).z, -m_eq * gamma * 1e-5);
  EXPECT_DOUBLE_EQ(sm::slider_force(sm::Slider::viscous, cap, fast, m_eq, dt, gamma, 0.0).z, -cap);
  EXPECT_EQ(sm::slider_force(sm::Slider::coulomb, cap, slow, m_eq, dt, 0.0, 1e-4).z, 0.0);
  EXPECT_DOUBLE_EQ(sm::slider_force(sm::Slider::coulomb, cap, slow, m_eq, dt, 0.0, 1e-6).z, -cap);
  EXPECT_THROW(sm::slider_from_name("sticky"), sm::ParamError);
}

// The coulomb slider takes a slip within the round-off of the normal speed for none (it would give it
// the full cap); stick and viscous give it a force in proportion, a round-off force.
TEST(ContactParts, CoulombSliderTakesASlipWithinTheRoundOffOfTheNormalSpeedForNone) {
  const double m_eq = 2e-8, dt = 1e-7, cap = 1e-4, gamma = 28340.1, v_n = 0.5;
  const double round_off = sm::slip_round_off(v_n);
  EXPECT_EQ(round_off, 8 * 0x1p-52 * v_n) << "8 ulps of |v_n|";
  EXPECT_EQ(sm::slip_round_off(0.5f), 8 * 0x1p-23f * 0.5f) << "in float, 8 of its ulps";
  const V3 within{0, 0, round_off}, beyond{0, 0, 2 * round_off};
  EXPECT_EQ(sm::norm(sm::slider_force(sm::Slider::coulomb, cap, within, m_eq, dt, gamma, 0.0, round_off)), 0.0);
  EXPECT_DOUBLE_EQ(sm::slider_force(sm::Slider::coulomb, cap, beyond, m_eq, dt, gamma, 0.0, round_off).z, -cap);
  for (sm::Slider kind : {sm::Slider::stick, sm::Slider::viscous}) {
    const double f = sm::slider_force(kind, cap, within, m_eq, dt, gamma, 0.0, round_off).z;
    EXPECT_LT(f, 0.0) << int(kind);
    EXPECT_LT(-f, 1e-12 * cap) << int(kind) << ": a round-off slip, a round-off force";
    EXPECT_EQ(f, sm::slider_force(kind, cap, within, m_eq, dt, gamma, 0.0).z) << int(kind) << ": unchanged";
  }
}

TEST(ContactParts, RollingTorqueIsDirectionalCappedAndIgnoresTwist) {
  const double m_eq = 3.6e-8, r = 125e-6, dt = 3e-7, fn = 3.5e-7, mu_r = 0.1;
  const V3 n{0, 0, 1};
  // pure twisting about the normal: no rolling torque
  EXPECT_EQ(sm::norm(sm::rolling_torque(mu_r, r, fn, n, V3{0, 0, 50}, m_eq, dt)), 0.0);
  // fast rolling: the constant torque mu_r r |F_n| against w (twist component dropped)
  const V3 t = sm::rolling_torque(mu_r, r, fn, n, V3{0, 100, 7}, m_eq, dt);
  EXPECT_DOUBLE_EQ(t.y, -mu_r * r * fn);
  EXPECT_EQ(t.x, 0.0);
  EXPECT_EQ(t.z, 0.0);
  // slow rolling: limited to remove half the relative spin of inertia (2/5) m_eq r^2 per step
  const double w = 1e-9;
  const V3 s = sm::rolling_torque(mu_r, r, fn, n, V3{w, 0, 0}, m_eq, dt);
  EXPECT_NEAR(s.x * dt / (0.4 * m_eq * r * r), -0.5 * w, 1e-24);
}

TEST(ContactParts, TangentialSpringRotatesWithTheContactAndRespectsTheCap) {
  // An elongation left over from a contact whose normal was z, now seen with a tilted normal.
  const double c = std::cos(0.3), s = std::sin(0.3);
  const V3 n{s, 0, c};
  double hist[3] = {2e-7, 1e-7, 0};
  const double len = std::sqrt(5e-14);
  const V3 f = sm::tangential_spring(n, V3{0, 0, 0}, 100.0, 0.0, 1.0, 1e-7, hist);
  const V3 e{hist[0], hist[1], hist[2]};
  EXPECT_NEAR(sm::dot(e, n), 0.0, 1e-22) << "rotated into the tangent plane";
  EXPECT_NEAR(sm::norm(e), len, 1e-20) << "length kept";
  EXPECT_NEAR(sm::norm(f + e * 100.0), 0.0, 1e-18) << "uncapped: F = -k s";
  // capped: |F| = cap and the stored elongation reproduces the capped force with the dashpot
  double h2[3] = {1e-6, 0, 0};
  const V3 v{0, 3e-3, 0};
  const double k = 500, beta = 1e-5, cap = 2e-4;
  const V3 g = sm::tangential_spring(V3{0, 0, 1}, v, k, beta, cap, 1e-7, h2);
  EXPECT_NEAR(sm::norm(g), cap, 1e-18);
  EXPECT_NEAR(sm::norm(g + V3{h2[0], h2[1], h2[2]} * k + v * beta), 0.0, 1e-18);
}

// What each law tells the host for its time step, against the equations in its header.
TEST(ContactFrequencies, HookeSliderHasOmega0EverywhereAndTheRestitutionZeta) {
  const auto law = sm::test::bind_law<sm::HookeSlider>();
  for (double m : {1e-9, 3.6243e-8, 1e-5}) EXPECT_DOUBLE_EQ(law.natural_frequency(m, 1e-4), 0.5 / 2.5e-6);
  EXPECT_NEAR(law.damping_ratio(3.6e-8, 1e-4), 0.070850, 5e-7);
  EXPECT_TRUE(law.makes_torque());
  // K_n = m_eq V_max^2 / Delta_max^2: the peer runs' 1449.71 N/m against a wall (m_eq = m)
  const double m = sm::test::study_sphere().m;
  sm::ContactState<double> c{{0, 0, 1}, 1e-6, 0, {0, 0, 0}, {0, 0, 0}, m, 125e-6, 1e-7};
  EXPECT_NEAR(law(c, static_cast<double *>(nullptr)).normal / 1e-6, 1449.71, 0.005);
  c.m_eq = m / 2;
  EXPECT_NEAR(law(c, static_cast<double *>(nullptr)).normal / 1e-6, 724.857, 0.0005);
  const auto frictionless = sm::test::bind_law<sm::HookeSlider>({{"friction", 0.0}});
  EXPECT_FALSE(frictionless.makes_torque());
  const auto corrected = sm::test::bind_law<sm::HookeSlider>({{"clamp_normal", true}, {"clamp_correction", true}});
  EXPECT_NEAR(sm::clamped_restitution(corrected.damping_ratio(1, 1)), 0.8, 1e-12);
  EXPECT_THROW(sm::test::bind_law<sm::HookeSlider>({{"clamp_correction", true}}), sm::ParamError);
}

TEST(ContactFrequencies, HookeHistoryReportsTheFasterOfNormalAndTangentialModes) {
  const double w0 = 0.5 / 2.5e-6;
  EXPECT_DOUBLE_EQ(sm::test::bind_law<sm::HookeHistory>().natural_frequency(1e-8, 1e-4), w0);
  EXPECT_DOUBLE_EQ(
      sm::test::bind_law<sm::HookeHistory>({{"tangential_stiffness_ratio", 1.0}}).natural_frequency(1e-8, 1e-4),
      w0 * std::sqrt(3.5));
  EXPECT_NEAR(sm::test::bind_law<sm::HookeHistory>({{"restitution", 0.5}}).damping_ratio(1, 1), 0.215454, 1e-6);
}

TEST(ContactFrequencies, HertzMindlinAtTheImpactSpeedVmax) {
  const double e = 1e9, nu = 0.3, m = 3.6243e-8, r = 125e-6, v = 0.5;
  const auto law = sm::test::bind_law<sm::HertzMindlin>({{"youngs_modulus", e}, {"poisson_ratio", nu}});
  const double es = e / (2 * (1 - nu * nu)), gs = e / (4 * (1 + nu) * (2 - nu));
  // undamped Hertz impact: (1/2) m v^2 = (8/15) E* sqrt(R) delta^(5/2)
  const double delta = std::pow(15 * m * v * v / (16 * es * std::sqrt(r)), 0.4);
  EXPECT_NEAR(0.5 * m * v * v, 8.0 / 15.0 * es * std::sqrt(r) * std::pow(delta, 2.5), 1e-12 * m * v * v);
  const double wn = std::sqrt(2 * es * std::sqrt(r * delta) / m);
  const double wt = std::sqrt(8 * gs * std::sqrt(r * delta) / (2.0 / 7.0 * m));
  EXPECT_NEAR(law.natural_frequency(m, r), std::max(wn, wt), 1e-12 * wt);
  EXPECT_GT(wt, wn) << "for nu = 0.3 the Mindlin mode is the faster one";
  const double le = std::log(0.8), alpha_drdm = -2 * std::sqrt(5.0 / 6.0) * le / std::sqrt(le * le + sm::pi * sm::pi);
  EXPECT_DOUBLE_EQ(law.damping_ratio(m, r), alpha_drdm / 2);
}

// The damping factor against the dimensionless Hertz impact x'' = -(x^1.5 + sqrt(1.5) alpha x^0.25 x'):
// unclamped, Di Renzo-Di Maio's closed form returns eps (to the solver's converged accuracy, 1e-6 at
// h = 1e-4); clamped, the calibrated alpha returns eps, and the uncalibrated one would not.
TEST(HertzDamping, DiRenzoDiMaioIsExactUnclampedAndTheClampIsCalibrated) {
  using H = sm::HertzMindlin;
  for (double eps : {0.9, 0.8, 0.5, 0.1}) {
    const double a_free = H::alpha_for_restitution(eps, false), a_clamped = H::alpha_for_restitution(eps, true);
    EXPECT_NEAR(H::restitution_at(a_free, false, 1e-4), eps, 1e-6) << eps;
    EXPECT_NEAR(H::restitution_at(a_clamped, true, 1e-4), eps, 3e-5) << eps;
    EXPECT_GT(H::restitution_at(a_free, true, 1e-4), eps + 1e-3) << "clamping raises the restitution";
  }
  EXPECT_EQ(H::alpha_for_restitution(1.0, true), 0.0);
  EXPECT_NEAR(H::alpha_for_restitution(0.0, false), 2 * std::sqrt(5.0 / 6.0), 1e-15);
  EXPECT_LT(H::restitution_at(2 * std::sqrt(5.0 / 6.0) + 1e-3, false), 1e-6) << "beyond it: no rebound";
  EXPECT_THROW(H::alpha_for_restitution(0.0, true), sm::ParamError);
}

}  // namespace
