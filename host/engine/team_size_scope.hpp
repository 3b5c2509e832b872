// Runs a scope on fewer threads than the caller's setting: small loops and the team tuner's choice
// (engine/team_tuner.hpp). Internal to the engine's Simulation.
#pragma once
#ifdef _OPENMP
#include <omp.h>
#endif

namespace spreadmap::engine {

// Runs the enclosing scope on at most `most` threads (0: as many as the caller's setting), restoring
// the caller's thread count (the OpenMP setting the thread team follows) on exit, exceptions
// included. Affects only the calling thread's runs.
class TeamSizeScope {
 public:
  explicit TeamSizeScope(int most) {
#ifdef _OPENMP
    if (most > 0 && omp_get_max_threads() > most) {
      saved_ = omp_get_max_threads();
      omp_set_num_threads(most);
    }
#else
    (void)most;
#endif
  }
  ~TeamSizeScope() {
#ifdef _OPENMP
    if (saved_ > 0) omp_set_num_threads(saved_);
#endif
  }
  TeamSizeScope(const TeamSizeScope &) = delete;
  TeamSizeScope &operator=(const TeamSizeScope &) = delete;

 private:
  int saved_ = 0;
};

}  // namespace spreadmap::engine
