// Spreading cases stepped at once, each from its own thread, against each stepped alone: what lets a
// design's cases run side by side (the local executor's pool of case threads; on a GPU, one stream a
// case, cuda/resident_stepper.hpp). The scene is the quickstart's (roller, substrate, periodic strip)
// with a low heap of 400 spheres that settles in a few thousand steps; the cases differ in the
// roller's speed, from one settled heap.
#pragma once
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "unit/built_plugins.hpp"
#include "workflow/file/workflow.hpp"
#include "workflow/spreading/case_setup.hpp"
#include "workflow/spreading/scene_section.hpp"
#include "workflow/stage_table.hpp"

inline spreadmap::Scene small_spreading_scene(const std::string &precision) {
  namespace sm = spreadmap;
  sm::Diagnostics diag;
  const auto resolved =
      sm::resolve_scene(sm::load_workflow(std::filesystem::path(SPREADMAP_SOURCE_DIR) / "workflows" / "quickstart.yaml",
                                          sm::stage_names()),
                        built_plugins(), diag);
  diag.throw_if_any();
  sm::Scene scene = *resolved;
  scene.powder.count = 400;  // a low heap over the preset's 6-13 mm (a 3 mm heap would sit under the roller)
  scene.powder.settle_time = 0.02;
  scene.spreader.params["U"] = 0.1;
  scene.precision = precision == "float" ? sm::Precision::float32 : sm::Precision::float64;
  return scene;
}

// One case per roller speed [m/s], `steps` steps on `backend`: each alone, one after another, then all
// at once, each from its own thread; every end state, list and counter must be the same.
inline void expect_cases_at_once_end_as_alone(const std::string &backend, const std::vector<double> &speeds,
                                              std::uint64_t steps) {
  namespace sm = spreadmap;
  struct EndState {
    std::vector<double> kinematics;
    std::size_t size, list_entries;
    std::uint64_t list_builds;
  };
  auto end_state = [](const sm::SpreadingRun<double> &r) {
    return EndState{r.sim.state().kinematics_by_id(), r.sim.size(), r.sim.list_entries(), r.sim.counters().list_builds};
  };
  sm::Scene scene = small_spreading_scene("double");
  scene.backend = "cpu";
  const auto heap = sm::settle_heap<double>(scene, built_plugins(), "concurrent cases", "scene.json");
  scene.backend = backend;
  auto make = [&](double speed) {
    sm::Scene s = scene;
    s.spreader.params["U"] = speed;
    return sm::make_spreading_run<double>(s, built_plugins(), heap, "scene.json");
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
    EXPECT_NE(runs[c]->sim.backend_name().find(backend), std::string::npos) << runs[c]->sim.backend_name();
    const EndState together = end_state(*runs[c]);
    EXPECT_EQ(together.size, alone[c].size) << "case " << c;
    EXPECT_EQ(together.list_entries, alone[c].list_entries) << "case " << c;
    EXPECT_EQ(together.list_builds, alone[c].list_builds) << "case " << c;
    ASSERT_EQ(together.kinematics.size(), alone[c].kinematics.size()) << "case " << c;
    EXPECT_EQ(std::memcmp(together.kinematics.data(), alone[c].kinematics.data(),
                          together.kinematics.size() * sizeof(double)),
              0)
        << "case " << c << " (U = " << speeds[c] << " m/s) stepped beside the others differs from it alone";
  }
  // the speeds part the cases: a mix-up of the cases' data would not go unseen
  EXPECT_NE(std::memcmp(alone.front().kinematics.data(), alone.back().kinematics.data(),
                        alone.front().kinematics.size() * sizeof(double)),
            0);
}
