// How many threads a simulation's steps use, chosen by measuring. The loops of a step split their
// work statically between the threads, so one thread that shares its core with another process
// holds the whole team back at the end of every loop: on 2 cores beside one busy process, 2 threads
// ran at 0.23x one thread. The tuner times windows of steps at the current count and, now and then,
// one window at a neighbouring count (one thread fewer or one more, never more than allowed); it
// moves to a neighbour that is faster, and probes less often while none is. Results do not depend on
// the thread count (the engine is bitwise identical for any), so moving changes no bit of them.
#pragma once

namespace spreadmap::engine {

class TeamTuner {
 public:
  // A window: at least this many steps and this many seconds, so that a list build or a timer tick
  // is a small part of it.
  static constexpr int window_steps = 8;
  static constexpr double window_seconds = 0.01;
  // A neighbour must be this much faster per step to be taken; probes come every 4 to 64 windows.
  static constexpr double better = 0.95;
  static constexpr int soonest = 4, latest = 64;

  // Starts over with `most` threads allowed (and used).
  void reset(int most);
  int most() const { return most_; }
  // The threads of the next step.
  int threads() const { return probing_ ? probe_ : current_; }
  // After each step: how long it took.
  void stepped(double seconds);

 private:
  void end_window(double per_step);

  int most_ = 1, current_ = 1, probe_ = 1;
  bool probing_ = false, probe_fewer_ = true;
  int steps_ = 0;
  double seconds_ = 0;
  double per_step_ = 0;  // the current count's seconds per step, its last window
  int interval_ = soonest, until_probe_ = soonest;
};

}  // namespace spreadmap::engine
