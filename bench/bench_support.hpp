// What the benchmarks share: the machine they ran on, as they print it, and their list arguments.
#pragma once
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

namespace spreadmap::bench {

// The processor's model name, from /proc/cpuinfo ("unknown" elsewhere).
inline std::string cpu_model() {
  std::ifstream in("/proc/cpuinfo");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind("model name", 0) == 0) return line.substr(line.find(':') + 2);
  return "unknown";
}

// The 1, 5 and 15 minute load averages: how busy the machine was besides the benchmark.
inline std::string load_average() {
  std::ifstream in("/proc/loadavg");
  std::string a, b, c;
  in >> a >> b >> c;
  return a + " " + b + " " + c;
}

// Prints "NAME: WHY" and NAME's usage line, and exits with status 2 (a bad command line).
[[noreturn]] inline void usage_exit(const char *name, const char *usage, const std::string &why) {
  std::fprintf(stderr, "%s: %s\nusage: %s %s\n", name, why.c_str(), name, usage);
  std::exit(2);
}

// A benchmark's command line, flag by flag: `for (Args args(argc, argv, usage); args.next();)`, then
// args.flag() and, for a flag with a value, args.value() (usage("missing value after ...") if none).
class Args {
 public:
  Args(int argc, char **argv, void (*usage)(const std::string &why)) : argc_(argc), argv_(argv), usage_(usage) {}
  bool next() {
    if (++k_ >= argc_) return false;
    flag_ = argv_[k_];
    return true;
  }
  const std::string &flag() const { return flag_; }
  std::string value() {
    if (k_ + 1 >= argc_) usage_("missing value after " + flag_);
    return argv_[++k_];
  }

 private:
  int argc_, k_ = 0;
  char **argv_;
  void (*usage_)(const std::string &why);
  std::string flag_;
};

// "1,2,8" as whole numbers, each at least 1.
inline std::vector<int> counts_in(const std::string &list) {
  std::vector<int> counts;
  for (std::size_t p = 0; p < list.size();) {
    const std::size_t q = std::min(list.find(',', p), list.size());
    counts.push_back(std::max(1, std::stoi(list.substr(p, q - p))));
    p = q + 1;
  }
  return counts;
}

}  // namespace spreadmap::bench
