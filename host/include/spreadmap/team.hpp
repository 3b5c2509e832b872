// This thread's place in the current OpenMP team, and the team size a parallel region would get:
// one thread of one when built without OpenMP. Loops split work by these so that each thread owns a
// fixed range, which keeps results independent of scheduling.
#pragma once
#ifdef _OPENMP
#include <omp.h>
#endif

namespace spreadmap {

struct TeamSlot {
  int thread = 0, threads = 1;
};

inline TeamSlot team_slot() {
#ifdef _OPENMP
  return {omp_get_thread_num(), omp_get_num_threads()};
#else
  return {};
#endif
}

inline int max_team_size() {
#ifdef _OPENMP
  return omp_get_max_threads();
#else
  return 1;
#endif
}

}  // namespace spreadmap
