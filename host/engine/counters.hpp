// Figures a run reports in its manifest (case.json).
#pragma once
#include <cstdint>

namespace spreadmap::engine {

// Where step() spends its time, summed over the steps [s]: the kicks and drifts, the neighbour-list
// rebuilds, the particle pairs, the plane walls, the geometries (spreaders), and the rest (overlap
// checks, sleeping, the loop's set-up). A handful of clock reads a step: ~0.1 % of a 5000-sphere step.
struct StepProfile {
  double integrate = 0, neighbours = 0, pairs = 0, planes = 0, geometries = 0, other = 0;
  double total() const { return integrate + neighbours + pairs + planes + geometries + other; }
};

struct RunCounters {
  std::uint64_t steps = 0;               // steps taken by this object (a resumed run continues the count)
  double wall_seconds = 0;               // time spent inside step() [s]
  double particle_steps = 0;             // sum over steps of the particle count
  double integrated_particle_steps = 0;  // the same for the particles awake (not asleep)
  std::uint64_t removed = 0;             // particles that left the domain through an open face
  std::uint64_t list_builds = 0;         // neighbour-list rebuilds
  StepProfile profile;                   // where wall_seconds went (CPU steps; a device step is `other`)

  double particle_steps_per_second() const { return wall_seconds > 0 ? particle_steps / wall_seconds : 0; }
};

}  // namespace spreadmap::engine
