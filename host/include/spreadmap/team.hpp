// This thread's place in the current OpenMP team, and the team size a parallel region would get:
// one thread of one when built without OpenMP. Loops split work by these so that each thread owns a
// fixed range, which keeps results independent of scheduling.
#pragma once
#include <cstddef>
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

// Thread `team`'s share [lo, hi) of n items: contiguous ranges of equal size, in thread order.
struct TeamRange {
  std::size_t lo, hi;
};
inline TeamRange team_share(std::size_t n, TeamSlot team) {
  return {n * std::size_t(team.thread) / std::size_t(team.threads),
          n * std::size_t(team.thread + 1) / std::size_t(team.threads)};
}

// Runs body(TeamSlot) on each thread of a new team, or on the caller alone when the team would
// have one thread. A region of one thread is not free: once the process has had a larger team,
// libgomp wakes its idle threads with a system call at every region (a few microseconds each, about
// 5 % of a step on one thread). A barrier inside body is then a no-op (an orphaned barrier).
template <class Body> void run_team(Body &&body) {
#ifdef _OPENMP
  if (omp_get_max_threads() > 1) {
#pragma omp parallel
    body(team_slot());
    return;
  }
#endif
  body(TeamSlot{});
}

// body(i) for i in [0, n), split into equal contiguous ranges, one per thread of the team (the
// static schedule), or on the caller alone when the team would have one thread or `parallel` is false.
template <class Body> void parallel_for(long long n, Body &&body, bool parallel = true) {
#ifdef _OPENMP
  if (parallel && omp_get_max_threads() > 1) {
#pragma omp parallel for schedule(static)
    for (long long i = 0; i < n; ++i) body(i);
    return;
  }
#else
  (void)parallel;
#endif
  for (long long i = 0; i < n; ++i) body(i);
}

}  // namespace spreadmap
