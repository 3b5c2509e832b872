// Teams of threads for the engine's loops. Loops split work into fixed contiguous ranges, one per
// thread, which keeps results independent of scheduling. A loop runs on the team it is given: the
// engine's own (engine/thread_team.hpp), whose threads wait for work and for each other by spinning in
// user space; with no team (null) it runs in an OpenMP parallel region. One thread of one when built
// without OpenMP. Internal to the engine: plugins are handed ranges and queues, never threads
// (spreadmap/batch.hpp).
#pragma once
#include <cstddef>
#include <type_traits>
#ifdef _OPENMP
#include <omp.h>
#endif

namespace spreadmap {

// A thread's place in a run. cuts, when not null: how the host wants a loop over cuts_for items split
// (thread t takes [cuts[t], cuts[t + 1])). The host sets them to its particles' owners in a step, the
// threads that evaluate their pairs, so that every loop over the particles leaves a particle's data
// in one core's cache; team_share follows them.
struct TeamSlot {
  int thread = 0, threads = 1;
  const std::size_t *cuts = nullptr;
  std::size_t cuts_for = 0;
};

// A team of threads that runs a body once on each of its threads (engine/thread_team.hpp).
struct Team {
  void *self;
  int (*size)(void *self);                                                // threads a run would get now
  void (*run)(void *self, void (*body)(void *arg, TeamSlot), void *arg);  // returns when all are done
  void (*barrier)(void *self);                                            // inside a run: waits for its threads
};

// The number of threads a run would get: the OpenMP setting (OMP_NUM_THREADS, omp_set_num_threads).
inline int max_team_size() {
#ifdef _OPENMP
  return omp_get_max_threads();
#else
  return 1;
#endif
}

// Thread `team`'s share [lo, hi) of n items: contiguous ranges in thread order, the host's cuts when
// they are for n items, else of equal size.
struct TeamRange {
  std::size_t lo, hi;
};
inline TeamRange team_share(std::size_t n, TeamSlot team) {
  if (team.cuts && n == team.cuts_for) return {team.cuts[team.thread], team.cuts[team.thread + 1]};
  return {n * std::size_t(team.thread) / std::size_t(team.threads),
          n * std::size_t(team.thread + 1) / std::size_t(team.threads)};
}

// Runs body(TeamSlot) on each thread of `team` (an OpenMP region when null), or on the caller alone
// when the team would have one thread: a region of one thread is not free (libgomp wakes its idle
// threads with a system call at every region once the process has had a larger team). Inside body,
// team_barrier waits for the team's other threads.
template <class Body> void run_team(const Team *team, Body &&body) {
  using B = std::remove_reference_t<Body>;
  if (team) {
    if (team->size(team->self) > 1) {
      team->run(
          team->self, [](void *arg, TeamSlot slot) { (*static_cast<B *>(arg))(slot); }, &body);
      return;
    }
  }
#ifdef _OPENMP
  else if (omp_get_max_threads() > 1) {
#pragma omp parallel
    body(TeamSlot{omp_get_thread_num(), omp_get_num_threads()});
    return;
  }
#endif
  body(TeamSlot{});
}

// Inside run_team's body: returns once every thread of the run has called it.
inline void team_barrier(const Team *team) {
  if (team) {
    team->barrier(team->self);
    return;
  }
#ifdef _OPENMP
#pragma omp barrier
#endif
}

// body(i) for i in [0, n), in contiguous ranges of equal size, one per thread of the team, or on the
// caller alone when the team would have one thread or `parallel` is false.
template <class Body> void parallel_for(const Team *team, long long n, Body &&body, bool parallel = true) {
  if (!parallel) {
    for (long long i = 0; i < n; ++i) body(i);
    return;
  }
  run_team(team, [&](TeamSlot slot) {
    const TeamRange r = team_share(std::size_t(n), slot);
    for (auto i = static_cast<long long>(r.lo); i < static_cast<long long>(r.hi); ++i) body(i);
  });
}

}  // namespace spreadmap
