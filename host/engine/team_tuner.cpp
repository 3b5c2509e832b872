#include <engine/team_tuner.hpp>

#include <algorithm>

namespace spreadmap::engine {

void TeamTuner::reset(int most) {
  *this = TeamTuner();
  most_ = current_ = probe_ = std::max(1, most);
}

void TeamTuner::stepped(double seconds) {
  if (most_ <= 1) return;
  ++steps_;
  seconds_ += seconds;
  if (steps_ < window_steps || seconds_ < window_seconds) return;
  const double per_step = seconds_ / steps_;
  steps_ = 0;
  seconds_ = 0;
  end_window(per_step);
}

void TeamTuner::end_window(double per_step) {
  if (probing_) {
    probing_ = false;
    if (per_step < better * per_step_) {  // the neighbour is faster: move, and look further soon
      current_ = probe_;
      per_step_ = per_step;
      interval_ = soonest;
    } else {  // it is not: keep looking the other way first, and less often
      probe_fewer_ = !probe_fewer_;
      interval_ = std::min(2 * interval_, latest);
    }
    until_probe_ = interval_;
    return;
  }
  per_step_ = per_step;
  if (--until_probe_ > 0) return;
  const bool fewer = current_ == most_ || (probe_fewer_ && current_ > 1);
  probe_ = fewer ? current_ - 1 : current_ + 1;
  probing_ = true;
}

}  // namespace spreadmap::engine
