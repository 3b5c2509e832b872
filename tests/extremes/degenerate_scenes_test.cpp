// The smallest scenes: no powder at all, and a single sphere.
#include <gtest/gtest.h>

#include <engine/errors.hpp>

#include <cmath>
#include <limits>

#include "extremes/watch.hpp"

using namespace spreadmap::extremes;
namespace engine = spreadmap::engine;

TEST(EmptyHeap, AutomaticStepIsRefusedClearly) {
  // No sphere, no contact to take a stable step from: a clear refusal, not a step of 0 or inf.
  SceneSpec spec;
  spec.count = 0;
  Scene scene(spec);
  EXPECT_EQ(scene.sim().critical_dt(), std::numeric_limits<double>::infinity());
  try {
    scene.sim().step();
    FAIL() << "an automatic step was chosen with no particles";
  } catch (const engine::SetupError &e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("no particles"), std::string::npos) << what;
    EXPECT_NE(what.find("set dt"), std::string::npos) << what;
  }
}

TEST(EmptyHeap, RollerPassesOverNothing) {
  // With a step given, an empty scene runs: the roller travels, nothing is created, lost or NaN.
  SceneSpec spec;
  spec.count = 0;
  spec.U = 0.5;
  spec.omega = -100;
  spec.dt = 1e-5;
  Scene scene(spec);
  const Watch w = run_watched(scene, scene.spreading_time() + 0.01, 100);
  EXPECT_EQ(w.stopped, "");
  EXPECT_EQ(scene.sim().size(), 0u);
  EXPECT_EQ(scene.sim().removed_count(), 0u);
  EXPECT_NEAR(scene.sim().time(), scene.spreading_time() + 0.01, 1e-5);
  EXPECT_EQ(scene.sim().state().size(), 0u);
}

TEST(SingleSphere, DeadSphereComesToRestAtItsStaticOverlap) {
  // Restitution 0.01, friction 1: dropped 1 mm, it stops bouncing and rests where K delta = m g,
  // K = m omega0^2 against a wall (hooke_slider), i.e. delta = g / omega0^2.
  SceneSpec spec;
  spec.U = 0;
  spec.count = 1;
  spec.drop = 1e-3;
  spec.particles = spec.substrate = {0.01, 1.0};
  Scene scene(spec);
  const Watch w = run_watched(scene, 0.05, 200);
  ASSERT_EQ(w.stopped, "");
  ASSERT_EQ(w.non_finite, "");
  const auto s = scene.sim().state();
  ASSERT_EQ(s.size(), 1u);
  const double delta = 9.81 / (scene.omega0() * scene.omega0());
  EXPECT_NEAR(s.radius[0] - s.z[0], delta, 1e-3 * delta);
  EXPECT_LT(std::abs(s.vz[0]), 1e-9);
  EXPECT_LE(w.energy_growth_after(0), 1.0 + 1e-9) << "a dissipative bounce gained energy";
}

struct RollerCase {
  double U, omega;
};

class SingleSphereUnderRoller : public ::testing::TestWithParam<RollerCase> {};

TEST_P(SingleSphereUnderRoller, IsPushedAheadNeverSwallowed) {
  // One sphere on the substrate, met by the roller with a gap of 0.6 d: it cannot pass under (that
  // needs 0.4 d of overlap, twice the limit), so it is pushed ahead; it never ends inside the roller
  // or the substrate, nor behind the roller.
  SceneSpec spec;
  spec.count = 1;
  spec.U = GetParam().U;
  spec.omega = GetParam().omega;
  spec.gap = 0.6 * spec.diameter;
  Scene scene(spec);
  const Watch w = run_watched(scene, scene.spreading_time() + 0.01, 20);
  EXPECT_EQ(w.stopped, "");
  EXPECT_EQ(w.non_finite, "");
  EXPECT_LE(w.worst_substrate, 0.1);
  EXPECT_LE(w.worst_roller, 0.1);
  EXPECT_EQ(w.roller_inside, 0u);
  ASSERT_EQ(scene.sim().size(), 1u);
  spreadmap::sm_spreader_pose_v2 pose{};
  scene.roller().pose(scene.sim().time(), &pose);
  EXPECT_GT(scene.sim().state().x[0], pose.reference[0]) << "the sphere passed under a gap of 0.6 d";
  EXPECT_LE(w.energy_growth_after(scene.spreading_time()), 1.0 + 1e-3);
}

INSTANTIATE_TEST_SUITE_P(Roller, SingleSphereUnderRoller,
                         ::testing::Values(RollerCase{0.5, -100}, RollerCase{0.5, 0}, RollerCase{0.5, 50},
                                           RollerCase{0.1, 100}),
                         [](const auto &info) {
                           const auto &p = info.param;
                           return "U" + std::to_string(int(std::lround(p.U * 1e3))) + "_omega_" +
                                  (p.omega < 0 ? "minus" : "plus") + std::to_string(int(std::abs(p.omega)));
                         });

TEST(SingleSphere, WedgedUnderAForwardRollingRollerStopsTheRunClearly) {
  // U = 500 mm/s, omega = +100 rad/s (rolling: bottom surface at rest, front surface moving down)
  // over a gap of 0.6 d: friction drags the sphere down into the wedge between the roller and the
  // substrate, where it jams (the substrate's friction holds it) and the kinematic roller presses on.
  // No rigid-sphere answer exists; the engine must stop at the overlap limit with a clear error,
  // before the sphere is inside the roller or the substrate beyond it, and never pass it under.
  SceneSpec spec;
  spec.count = 1;
  spec.U = 0.5;
  spec.omega = 100;
  spec.gap = 0.6 * spec.diameter;
  Scene scene(spec);
  const Watch w = run_watched(scene, scene.spreading_time() + 0.01, 10);
  ASSERT_NE(w.stopped, "") << "the wedged sphere was squeezed through, or escaped";
  EXPECT_NE(w.stopped.find("overlap too large"), std::string::npos) << w.stopped;
  EXPECT_EQ(w.non_finite, "");
  EXPECT_LE(w.worst_roller, 0.1);
  EXPECT_LE(w.worst_substrate, 0.1);
  const auto s = scene.sim().state();
  ASSERT_EQ(first_non_finite(s), "");
  spreadmap::sm_spreader_pose_v2 pose{};
  scene.roller().pose(scene.sim().time(), &pose);
  EXPECT_GT(s.x[0], pose.reference[0]) << "the sphere passed under a gap of 0.6 d";
}
