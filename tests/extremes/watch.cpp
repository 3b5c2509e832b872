#include "extremes/watch.hpp"

#include <engine/errors.hpp>

#include <algorithm>

namespace spreadmap::extremes {

double Watch::energy_growth_after(double t_from) const {
  double first = -1, largest = 0;
  for (const auto &s : energy) {
    if (s.t < t_from) continue;
    if (first < 0) first = s.e.total();
    largest = std::max(largest, s.e.total());
  }
  return first > 0 ? largest / first : 0.0;
}

Energy Watch::first_energy_after(double t_from) const {
  for (const auto &s : energy)
    if (s.t >= t_from) return s.e;
  return {};
}

namespace {
void sample(const Scene &scene, Watch &w) {
  const auto &sim = scene.sim();
  const engine::ParticleSet s = sim.state();
  if (w.non_finite.empty()) w.non_finite = first_non_finite(s);
  if (!w.non_finite.empty()) return;  // nothing else is meaningful on NaN
  w.worst_substrate = std::max(w.worst_substrate, deepest_substrate_overlap(s));
  if (scene.has_roller()) {
    const RollerOverlap r = roller_overlap(scene.roller(), s, sim.time());
    w.worst_roller = std::max(w.worst_roller, r.deepest);
    w.roller_inside += r.centre_inside;
  }
  w.top_speed = std::max(w.top_speed, top_speed(s));
  w.energy.push_back({sim.time(), mechanical_energy(scene)});
}
}  // namespace

Watch run_watched(Scene &scene, double t_end, unsigned every) {
  Watch w;
  auto &sim = scene.sim();
  try {
    sample(scene, w);
    while (sim.time() + 0.5 * sim.dt() < t_end && w.non_finite.empty()) {
      sim.run_steps(every);
      sample(scene, w);
    }
  } catch (const engine::RunError &e) {
    w.stopped = e.what();
  } catch (const engine::SetupError &e) {
    w.stopped = e.what();
  }
  return w;
}

}  // namespace spreadmap::extremes
