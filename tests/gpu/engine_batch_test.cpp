// Cases that step at once on one GPU end bitwise as each ends alone. The resident stepper runs on its
// own CUDA stream (cuda/resident_stepper.hpp) and the simulate stage's pool steps each case from its
// own host thread; six spreading cases (the gpu tests' small scene at six roller speeds, from one
// settled heap) run 2000 steps one after another, then all six at once: every end state, list and
// counter is the same. Needs a CUDA device (label gpu): skipped, saying why, where there is none.
#include <gtest/gtest.h>

#include <cstring>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "gpu/spreading_scene.hpp"
#include "workflow/spreading/case_setup.hpp"

namespace sm = spreadmap;

namespace {

struct EndState {
  std::vector<double> kinematics;
  std::size_t size = 0, list_entries = 0;
  std::uint64_t list_builds = 0;
};

template <class Real> EndState end_state(const sm::SpreadingRun<Real> &r) {
  return {r.sim.state().kinematics_by_id(), r.sim.size(), r.sim.list_entries(), r.sim.counters().list_builds};
}

}  // namespace

TEST(EngineBatch, CasesSteppingAtOnceOnOneGpuEndAsEachAlone) {
  REQUIRE_CUDA_DEVICE();
  constexpr std::uint64_t steps = 2000;
  const double speeds[] = {0.04, 0.07, 0.1, 0.13, 0.16, 0.2};  // m/s
  sm::Scene scene = small_spreading_scene("double");
  scene.backend = "cpu";
  const auto heap = sm::settle_heap<double>(scene, registry(), "gpu batch test", "scene.json");
  scene.backend = "cuda";
  auto make = [&](double speed) {
    sm::Scene s = scene;
    s.spreader.params["U"] = speed;
    return sm::make_spreading_run<double>(s, registry(), heap, "scene.json");
  };

  std::vector<EndState> alone;
  for (double u : speeds) {
    auto r = make(u);
    r->sim.run_steps(steps);
    alone.push_back(end_state(*r));
  }

  std::vector<std::unique_ptr<sm::SpreadingRun<double>>> runs;
  for (double u : speeds) runs.push_back(make(u));
  std::vector<std::string> errors(runs.size());
  std::vector<std::thread> threads;
  for (std::size_t c = 0; c < runs.size(); ++c)
    threads.emplace_back([&, c] {
      try {
        runs[c]->sim.run_steps(steps);
      } catch (const std::exception &e) {
        errors[c] = e.what();
      }
    });
  for (auto &t : threads) t.join();

  for (std::size_t c = 0; c < runs.size(); ++c) {
    ASSERT_EQ(errors[c], "") << "case " << c;
    EXPECT_NE(runs[c]->sim.backend_name().find("cuda"), std::string::npos) << runs[c]->sim.backend_name();
    const EndState together = end_state(*runs[c]);
    EXPECT_EQ(together.size, alone[c].size) << "case " << c;
    EXPECT_EQ(together.list_entries, alone[c].list_entries) << "case " << c;
    EXPECT_EQ(together.list_builds, alone[c].list_builds) << "case " << c;
    ASSERT_EQ(together.kinematics.size(), alone[c].kinematics.size()) << "case " << c;
    EXPECT_EQ(std::memcmp(together.kinematics.data(), alone[c].kinematics.data(),
                          together.kinematics.size() * sizeof(double)),
              0)
        << "case " << c << " (U = " << speeds[c] << " m/s) stepped beside five others differs from it alone";
  }
  // the speeds part the cases: a batch of copies of one case would hide a mix-up of their data
  EXPECT_NE(
      std::memcmp(alone[0].kinematics.data(), alone[5].kinematics.data(), alone[0].kinematics.size() * sizeof(double)),
      0);
}
