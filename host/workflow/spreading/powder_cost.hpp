// What a case of the scene will cost, estimated from the scene before anything runs, and a warning
// when a size distribution's smallest particles make it impractical.
//
// Particles: the count, or the heap's volume over the mean sphere volume of the distribution. Step:
// time.step, else time.safety x dt_crit of the pair law for two of the smallest particles (dt_crit
// scales with the contact time: sqrt(m / k), the smallest mass with the law's stiffness there;
// engine/stability.hpp). Simulated time: settling + the spreader's pass + relax. Cost: particles x
// steps. Coarse graining is applied first, as the engine runs it.
#pragma once
#include <optional>
#include <string>

#include "core/registry.hpp"
#include "workflow/spreading/scene_model.hpp"

namespace spreadmap {

// About two hours at the 1.2e7 particle-steps/s of the quickstart on 2 cores.
inline constexpr double practical_particle_steps = 1e11;

struct CaseCost {
  double particles = 0;
  double smallest = 0, median = 0;      // smallest diameter, median by number [m]
  double step = 0, step_at_median = 0;  // dt, and dt if the smallest were of the median size [s]
  double simulated_time = 0;            // s
  double particle_steps() const { return particles * simulated_time / step; }
};

CaseCost estimate_case_cost(const Scene &scene, PluginRegistry &registry);

// For a size distribution (not a monodisperse powder) whose case costs more than
// practical_particle_steps: the numbers and the trades (coarse graining, a larger d_min), else nothing.
std::optional<std::string> powder_cost_warning(const Scene &scene, PluginRegistry &registry, const std::string &file);

}  // namespace spreadmap
