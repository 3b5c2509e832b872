// The engine's team of threads for the loops of a step.
// Its threads wait for work and for each other by spinning in user space, then sleep: an OpenMP
// region or barrier costs a futex system call (libgomp wakes waiters that way even when they spin),
// and on a machine where system calls are dear (a virtual machine with page-table isolation) that
// call and what it evicts were a good part of a two-thread step.
#pragma once
#include <engine/team.hpp>

#include <atomic>
#include <thread>
#include <vector>

namespace spreadmap::engine {

class ThreadTeam {
 public:
  ThreadTeam();
  ~ThreadTeam();
  ThreadTeam(const ThreadTeam &) = delete;
  ThreadTeam &operator=(const ThreadTeam &) = delete;

  const Team *view() const { return &view_; }
  // Until cleared (null): a run of `threads` threads tells its loops over n items to split them at
  // cuts (threads + 1 values), see TeamSlot.
  void set_cuts(const std::size_t *cuts, std::size_t n, int threads) {
    cuts_ = cuts;
    cuts_for_ = n;
    cuts_threads_ = threads;
  }

 private:
  static int size(void *self);
  static void run(void *self, void (*body)(void *, TeamSlot), void *arg);
  static void barrier(void *self);
  void run(void (*body)(void *, TeamSlot), void *arg);
  void barrier();
  void work(int thread, unsigned seen);
  void post(int threads);  // starts a run of `threads` threads; workers beyond it leave
  // Waits until done(value of a) holds: spins a while, then sleeps until told (wake).
  template <class Done> void await(const std::atomic<unsigned> &a, Done done);
  void wake(std::atomic<unsigned> &a);
  TeamSlot slot(int thread, int threads) const;

  Team view_;
  std::vector<std::thread> workers_;  // threads 1, 2, ... of a run; the caller is thread 0
  void (*body_)(void *, TeamSlot) = nullptr;
  void *arg_ = nullptr;
  const std::size_t *cuts_ = nullptr;
  std::size_t cuts_for_ = 0;
  int cuts_threads_ = 0;
  int threads_ = 1;                    // of the run in progress
  bool running_ = false;               // a run of several threads is in progress
  std::atomic<long long> spin_ns_{0};  // how long await spins before it sleeps
  // A run's number and its thread count in one word (count in the low byte), so that a worker reads
  // both at once: one that is late can only have missed runs it had no part in.
  alignas(64) std::atomic<unsigned> job_{0};
  alignas(64) std::atomic<unsigned> finished_{0};  // workers done with the run
  alignas(64) std::atomic<unsigned> arrived_{0};   // threads at the barrier
  alignas(64) std::atomic<unsigned> passed_{0};    // barriers passed
  alignas(64) std::atomic<unsigned> sleepers_{0};  // threads asleep in await
};

// The team of the calling thread (each thread that runs a simulation has its own).
ThreadTeam &this_thread_team_object();
const Team *this_thread_team();

}  // namespace spreadmap::engine
