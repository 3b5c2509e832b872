// Progress of long work: on a terminal a single rewritten line (case i/N, percent, elapsed, ETA);
// otherwise a plain log line at most every `interval` seconds. Thread-safe.
#pragma once
#include <chrono>
#include <mutex>
#include <string>

namespace spreadmap {

class Progress {
 public:
  Progress(std::string label, std::size_t total_items, bool quiet);
  // fraction of the current item in [0, 1]
  void update(std::size_t item, double fraction, const std::string &detail = "");
  void done_item();
  void finish();

 private:
  void print(double overall, const std::string &detail, bool force);
  std::string label_;
  std::size_t total_, done_ = 0;
  bool quiet_, tty_;
  std::chrono::steady_clock::time_point start_, last_;
  std::mutex mutex_;
};

}  // namespace spreadmap
