#include "workflow/scene/scene_run.hpp"

#include <algorithm>

namespace spreadmap::scene {

template <class Real>
bool advance_scene(SceneRun<Real> &run, double t, const typename engine::Simulation<Real>::StepCallback &keep_going,
                   std::uint64_t every) {
  auto &sim = *run.sim;
  std::vector<DelayedMotion> due;
  for (const auto &m : run.delayed)
    if (m.time >= sim.time() && m.time <= t) due.push_back(m);
  std::sort(due.begin(), due.end(), [](const auto &a, const auto &b) { return a.time < b.time; });
  for (const auto &m : due) {
    if (!sim.run_until(m.time, keep_going, every)) return false;
    sim.set_plane_wall_velocity(m.plane, m.velocity);
  }
  return sim.run_until(t, keep_going, every);
}

template bool advance_scene<double>(SceneRun<double> &, double, const engine::Simulation<double>::StepCallback &,
                                    std::uint64_t);
template bool advance_scene<float>(SceneRun<float> &, double, const engine::Simulation<float>::StepCallback &,
                                   std::uint64_t);

}  // namespace spreadmap::scene
