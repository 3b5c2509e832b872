#include <engine/thread_team.hpp>

#include <algorithm>
#include <chrono>

namespace spreadmap::engine {

namespace {
inline void relax() {
#if defined(__x86_64__) || defined(__i386__)
  __builtin_ia32_pause();
#endif
}

// Runs the calling thread is inside (a run inside a run takes its caller alone, and a barrier in it
// has no one to wait for).
thread_local int depth = 0;
struct Inside {
  Inside() { ++depth; }
  ~Inside() { --depth; }
};

constexpr unsigned count_bits = 8, count_mask = (1u << count_bits) - 1;
constexpr int most_threads = int(count_mask);
}  // namespace

ThreadTeam::ThreadTeam() : view_{this, &ThreadTeam::size, &ThreadTeam::run, &ThreadTeam::barrier} {}

ThreadTeam::~ThreadTeam() {
  if (!workers_.empty()) post(1);
  for (auto &w : workers_) w.join();
}

int ThreadTeam::size(void *) { return std::min(max_team_size(), most_threads); }
void ThreadTeam::run(void *self, void (*body)(void *, TeamSlot), void *arg) {
  static_cast<ThreadTeam *>(self)->run(body, arg);
}
void ThreadTeam::barrier(void *self) { static_cast<ThreadTeam *>(self)->barrier(); }

template <class Done> void ThreadTeam::await(const std::atomic<unsigned> &a, Done done) {
  const auto until =
      std::chrono::steady_clock::now() + std::chrono::nanoseconds(spin_ns_.load(std::memory_order_relaxed));
  for (int spins = 1;; ++spins) {
    if (done(a.load(std::memory_order_acquire))) return;
    relax();
    if (spins % 256 == 0 && std::chrono::steady_clock::now() > until) break;
  }
  // Asleep: whoever changes `a` next sees the sleeper (sequentially consistent order) and wakes it.
  sleepers_.fetch_add(1);
  for (unsigned v = a.load(); !done(v); v = a.load()) a.wait(v);
  sleepers_.fetch_sub(1);
}

void ThreadTeam::wake(std::atomic<unsigned> &a) {
  if (sleepers_.load() > 0) a.notify_all();
}

void ThreadTeam::post(int threads) {
  const unsigned number = (job_.load() >> count_bits) + 1;
  job_.store(number << count_bits | unsigned(threads));
  wake(job_);
}

void ThreadTeam::run(void (*body)(void *, TeamSlot), void *arg) {
  const int threads = size(this);
  if (threads <= 1 || depth > 0) {
    const Inside inside;
    body(arg, TeamSlot{});
    return;
  }
  // A waiting thread spins longer than the gaps between the loops of a step, and short enough that an
  // idle team gives its cores back at once; not at all when the team has more threads than the
  // machine has cores (it would spin while the thread it waits for cannot run).
  static const unsigned cores = std::max(1u, std::thread::hardware_concurrency());  // reads a file
  spin_ns_.store(unsigned(threads) > cores ? 0 : 200'000, std::memory_order_relaxed);
  while (int(workers_.size()) < threads - 1) {
    const int thread = int(workers_.size()) + 1;
    workers_.emplace_back([this, thread, seen = job_.load()] { work(thread, seen); });
  }
  body_ = body;
  arg_ = arg;
  threads_ = threads;
  running_ = true;
  finished_.store(0);
  post(threads);
  {
    const Inside inside;
    body(arg, slot(0, threads));
  }
  await(finished_, [threads](unsigned done) { return done == unsigned(threads - 1); });
  running_ = false;
  // workers beyond this run's count have left: a team that shrank keeps no idle threads
  for (std::size_t w = threads - 1; w < workers_.size(); ++w) workers_[w].join();
  workers_.resize(threads - 1);
}

void ThreadTeam::work(int thread, unsigned seen) {
  for (;;) {
    await(job_, [seen](unsigned job) { return job != seen; });
    seen = job_.load();
    const int threads = int(seen & count_mask);
    if (thread >= threads) return;
    {
      const Inside inside;
      body_(arg_, slot(thread, threads));
    }
    finished_.fetch_add(1);
    wake(finished_);
  }
}

void ThreadTeam::barrier() {
  if (!running_ || depth != 1) return;  // not in a run of several threads
  const unsigned passed = passed_.load(std::memory_order_acquire);
  if (arrived_.fetch_add(1) + 1 == unsigned(threads_)) {
    arrived_.store(0, std::memory_order_relaxed);
    passed_.fetch_add(1);
    wake(passed_);
  } else {
    await(passed_, [passed](unsigned now) { return now != passed; });
  }
}

TeamSlot ThreadTeam::slot(int thread, int threads) const {
  TeamSlot s{thread, threads};
  if (cuts_ && cuts_threads_ == threads) {
    s.cuts = cuts_;
    s.cuts_for = cuts_for_;
  }
  return s;
}

ThreadTeam &this_thread_team_object() {
  thread_local ThreadTeam team;
  return team;
}

const Team *this_thread_team() { return this_thread_team_object().view(); }

}  // namespace spreadmap::engine
