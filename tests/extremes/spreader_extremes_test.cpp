// The roller at the extremes of its settings, over a small heap (150 spheres, 3 layers): omega at
// +-50 and +-100 rad/s, U up to 500 mm/s, and a gap below one sphere diameter. Each run must finish
// (these are legitimate scenes, not unstable ones), with every number finite, no sphere sunk into the
// substrate or the roller beyond the overlap limit, no sphere lost other than through the open ends,
// and no energy gained once the roller has stopped.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <tuple>

#include "extremes/watch.hpp"

using namespace spreadmap::extremes;

namespace {

constexpr double overlap_limit = 0.1;  // the engine's default, as a fraction of the diameter
constexpr double relax = 0.01;         // [s] after the roller stops

// The truths every legitimate spreading run must hold.
void expect_clean_run(Scene &scene, const Watch &w, const std::string &label) {
  auto &sim = scene.sim();
  EXPECT_EQ(w.stopped, "") << label;
  EXPECT_EQ(w.non_finite, "") << label;
  EXPECT_LE(w.worst_substrate, overlap_limit) << label;
  EXPECT_LE(w.worst_roller, overlap_limit) << label;
  EXPECT_EQ(w.roller_inside, 0u) << label << ": sphere centres inside the roller";
  EXPECT_EQ(sim.size() + sim.removed_count(), scene.spec().count) << label << ": spheres lost";
  EXPECT_GE(sim.time(), scene.spreading_time() + relax - sim.dt()) << label << ": the run did not reach its end";
  // Once the roller rests nothing drives the spheres: dashpots, friction and removal only take
  // energy away. 1e-3 leaves room for the integrator's error at the force kinks (measured: no rise
  // at all on these scenes).
  EXPECT_LE(w.energy_growth_after(scene.spreading_time()), 1.0 + 1e-3) << label;
  std::printf(
      "%s: %zu spheres left, %llu removed, worst overlaps substrate %.3g %% roller %.3g %% of d, top speed "
      "%.3g m/s, energy growth at rest %.3g\n",
      label.c_str(), sim.size(), static_cast<unsigned long long>(sim.removed_count()), 100 * w.worst_substrate,
      100 * w.worst_roller, w.top_speed, w.energy_growth_after(scene.spreading_time()) - 1);
}

Watch spread(Scene &scene) { return run_watched(scene, scene.spreading_time() + relax); }

std::string label(const SceneSpec &s) {
  char text[96];
  std::snprintf(text, sizeof text, "U = %g mm/s, omega = %g rad/s, gap = %g um", s.U * 1e3, s.omega, s.gap * 1e6);
  return text;
}

}  // namespace

class RollerSpin : public ::testing::TestWithParam<double> {};

TEST_P(RollerSpin, FastSpinAtModerateSpeedStaysPhysical) {
  // Surface speeds up to U + |omega| R = 0.6 m/s against V_max = 0.5 m/s: the contacts stay within
  // their design overlap, and the forward-rolling cases (bottom moving backwards at up to 0.4 m/s)
  // drag spheres under the roller: none may end up inside it.
  SceneSpec spec;
  spec.U = 0.1;
  spec.omega = GetParam();
  Scene scene(spec);
  const Watch w = spread(scene);
  expect_clean_run(scene, w, label(spec));
}
INSTANTIATE_TEST_SUITE_P(Omega, RollerSpin, ::testing::Values(-100.0, -50.0, 50.0, 100.0), [](const auto &info) {
  return std::string(info.param < 0 ? "minus" : "plus") + std::to_string(int(std::abs(info.param)));
});

class RollerSpeed : public ::testing::TestWithParam<double> {};

TEST_P(RollerSpeed, FivehundredMillimetresPerSecond) {
  // U = 500 mm/s with the fastest spins: surface speeds up to 1 m/s, twice V_max.
  SceneSpec spec;
  spec.U = 0.5;
  spec.omega = GetParam();
  Scene scene(spec);
  const Watch w = spread(scene);
  expect_clean_run(scene, w, label(spec));
}
INSTANTIATE_TEST_SUITE_P(Omega, RollerSpeed, ::testing::Values(-100.0, 0.0, 100.0), [](const auto &info) {
  return std::string(info.param < 0 ? "minus" : "plus") + std::to_string(int(std::abs(info.param)));
});

class NarrowGap : public ::testing::TestWithParam<double> {};

TEST_P(NarrowGap, NoSphereSinksOrTunnels) {
  // A gap below one diameter. Contacts are soft: a sphere squeezed between the roller and the
  // substrate, each overlapping it by up to the limit (10 % of d), fits through a gap of 0.8 d, so at
  // 0.9 d a sphere may pass under the roller (overlaps within the limit). Below 0.8 d none can pass
  // without an overlap beyond the limit: none may end behind the roller's lowest line (x < axis) —
  // that would be tunnelling.
  SceneSpec spec;
  spec.gap = GetParam() * spec.diameter;
  Scene scene(spec);
  const Watch w = spread(scene);
  expect_clean_run(scene, w, label(spec));
  if (GetParam() >= 1 - 2 * overlap_limit) return;
  spreadmap::sm_spreader_pose_v2 pose{};
  scene.roller().pose(scene.sim().time(), &pose);
  const auto s = scene.sim().state();
  std::size_t behind = 0;
  for (std::size_t i = 0; i < s.size(); ++i) behind += s.x[i] < pose.reference[0] ? 1 : 0;
  EXPECT_EQ(behind, 0u) << "spheres passed under a roller whose gap is " << GetParam() << " d";
}
INSTANTIATE_TEST_SUITE_P(Gap, NarrowGap, ::testing::Values(0.9, 0.6, 0.2), [](const auto &info) {
  return "tenths_of_d_" + std::to_string(int(std::lround(info.param * 10)));
});

class RollerMaterials : public ::testing::TestWithParam<std::tuple<double, double>> {};

TEST_P(RollerMaterials, ExtremeMaterialsUnderTheFastestRoller) {
  // Restitution 0.01, 0.99 or 1 and friction 0 or 1 on every surface, spread at U = 500 mm/s with
  // omega = -100 rad/s (surface speed 1 m/s).
  const auto [restitution, friction] = GetParam();
  SceneSpec spec;
  spec.U = 0.5;
  spec.omega = -100;
  spec.particles = spec.substrate = spec.spreader_surface = {restitution, friction};
  Scene scene(spec);
  const Watch w = spread(scene);
  char text[64];
  std::snprintf(text, sizeof text, ", restitution %g, friction %g", restitution, friction);
  expect_clean_run(scene, w, label(spec) + text);
}
INSTANTIATE_TEST_SUITE_P(RestitutionFriction, RollerMaterials,
                         ::testing::Combine(::testing::Values(0.01, 0.99, 1.0), ::testing::Values(0.0, 1.0)),
                         [](const auto &info) {
                           return "e" + std::to_string(int(std::lround(std::get<0>(info.param) * 100))) + "_mu" +
                                  std::to_string(int(std::get<1>(info.param)));
                         });
