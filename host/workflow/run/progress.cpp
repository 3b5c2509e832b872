#include "workflow/run/progress.hpp"

#include <spdlog/spdlog.h>
#include <unistd.h>

#include <cstdio>

namespace spreadmap {

Progress::Progress(std::string label, std::size_t total_items, bool quiet)
    : label_(std::move(label)),
      total_(total_items),
      quiet_(quiet),
      tty_(::isatty(2) != 0),
      start_(std::chrono::steady_clock::now()),
      last_(start_ - std::chrono::hours(1)) {}

static std::string hms(double s) {
  char buf[32];
  const long t = static_cast<long>(s + 0.5);
  std::snprintf(buf, sizeof buf, "%ld:%02ld:%02ld", t / 3600, (t / 60) % 60, t % 60);
  return buf;
}

void Progress::print(double overall, const std::string &detail, bool force) {
  if (quiet_) return;
  const auto now = std::chrono::steady_clock::now();
  const double since = std::chrono::duration<double>(now - last_).count();
  if (!force && since < (tty_ ? 0.5 : 15.0)) return;
  last_ = now;
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  const std::string eta = overall > 1e-3 ? hms(elapsed * (1 - overall) / overall) : "--:--:--";
  char line[256];
  std::snprintf(line, sizeof line, "%s %zu/%zu %5.1f%% elapsed %s ETA %s %s", label_.c_str(),
                std::min(done_ + 1, total_), total_, 100 * overall, hms(elapsed).c_str(), eta.c_str(), detail.c_str());
  if (tty_) {
    std::fprintf(stderr, "\r%-110s", line);
    std::fflush(stderr);
  } else {
    spdlog::info("{}", line);
  }
}

void Progress::update(std::size_t, double fraction, const std::string &detail) {
  std::lock_guard<std::mutex> lock(mutex_);
  print(total_ ? (done_ + fraction) / double(total_) : 1.0, detail, false);
}

void Progress::done_item() {
  std::lock_guard<std::mutex> lock(mutex_);
  ++done_;
}

void Progress::finish() {
  std::lock_guard<std::mutex> lock(mutex_);
  if (!quiet_ && tty_) std::fprintf(stderr, "\r%-110s\r", "");
}

}  // namespace spreadmap
