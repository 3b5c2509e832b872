// The quickstart run the integration tests read: workflows/quickstart.yaml (the README's first
// command, without the build) run once into <build>/test-runs/quickstart, resumed by every test
// process (which recomputes nothing), one process at a time.
#pragma once
#include <gtest/gtest.h>

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "analysis/table.hpp"

namespace quickstart {

namespace fs = std::filesystem;
using spreadmap::analysis::Table;

inline const fs::path run_dir = fs::path(SPREADMAP_BINARY_DIR) / "test-runs" / "quickstart";
inline const std::string exe = std::string(SPREADMAP_BINARY_DIR) + "/bin/spreadmap";

// A shell command's exit status; its stdout and stderr together into *out.
inline int shell(const std::string &command, std::string *out = nullptr) {
  const std::string cmd = command + " 2>&1";
  FILE *p = popen(cmd.c_str(), "r");
  std::string text;
  char buf[4096];
  while (p && fgets(buf, sizeof buf, p)) text += buf;
  const int status = p ? pclose(p) : -1;
  if (out) *out = text;
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

inline int run(const std::string &args, std::string *out = nullptr) { return shell(exe + " " + args, out); }

// Held while this process runs the workflow into run_dir: the other test processes wait for it.
class RunLock {
 public:
  RunLock() {
    fs::create_directories(run_dir.parent_path());
    fd_ = ::open((run_dir.string() + ".lock").c_str(), O_CREAT | O_RDWR | O_CLOEXEC, 0644);
    if (fd_ >= 0) ::flock(fd_, LOCK_EX);
  }
  ~RunLock() {
    if (fd_ >= 0) ::close(fd_);  // releases the lock
  }
  RunLock(const RunLock &) = delete;
  RunLock &operator=(const RunLock &) = delete;

 private:
  int fd_ = -1;
};

inline nlohmann::json json_file(const fs::path &p) {
  std::ifstream in(p);
  return nlohmann::json::parse(in);
}

class Quickstart : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    // ctest runs each test of this suite in a process of its own, several at once: one process at a
    // time runs the workflow, the others wait and then resume it (which recomputes nothing).
    const RunLock lock;
    std::string log;
    status_ = run("run " + std::string(SPREADMAP_SOURCE_DIR) + "/workflows/quickstart.yaml --jobs 2 --quiet --out " +
                      run_dir.string(),
                  &log);
    log_ = log;
  }
  inline static int status_ = -1;
  inline static std::string log_;
};

}  // namespace quickstart

