// Figures a run reports in its manifest (case.json).
#pragma once
#include <cstdint>

namespace spreadmap::engine {

struct RunCounters {
  std::uint64_t steps = 0;               // steps taken by this object (a resumed run continues the count)
  double wall_seconds = 0;               // time spent inside step() [s]
  double particle_steps = 0;             // sum over steps of the particle count
  double integrated_particle_steps = 0;  // the same for the particles awake (not asleep)
  std::uint64_t removed = 0;             // particles that left the domain through an open face
  std::uint64_t list_builds = 0;         // neighbour-list rebuilds

  double particle_steps_per_second() const { return wall_seconds > 0 ? particle_steps / wall_seconds : 0; }
};

}  // namespace spreadmap::engine
