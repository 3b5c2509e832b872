// Runs the real spreadmap binary as a child process, the way a user does: arguments, environment
// and working folder in; exit status, stdout and stderr out. A child can also be started, signalled
// and waited for (kill-and-resume). No shell is involved, so paths need no quoting.
#pragma once
#include <sys/types.h>

#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace spreadmap::test {

namespace fs = std::filesystem;

struct Command {
  std::vector<std::string> args;           // without the program
  fs::path program;                        // empty = spreadmap_binary()
  std::map<std::string, std::string> env;  // set (or overridden) in the child's environment
  fs::path cwd;                            // empty = the test's
};

struct Outcome {
  bool exited = false;  // false: killed by a signal (a crash, for these tests)
  int exit_code = -1;
  int signal = 0;
  std::string out, err;
  std::string describe() const;  // "exit 2" / "signal 11" and stderr, for assertion messages
};

// The binary under test: <build>/bin/spreadmap.
fs::path spreadmap_binary();

class Child {
 public:
  explicit Child(const Command &command);
  ~Child();  // kills a child still running
  Child(const Child &) = delete;
  Child &operator=(const Child &) = delete;
  void signal(int sig) const;
  pid_t pid() const { return pid_; }
  bool running();
  Outcome wait();

 private:
  pid_t pid_ = -1;
  fs::path dir_;
  bool reaped_ = false;
  Outcome outcome_;
};

Outcome run(const Command &command);

// Text a clean error never contains: sanitizer reports, uncaught exceptions, raw library errors.
std::string crash_marker(const std::string &err);  // the marker found, or ""

}  // namespace spreadmap::test
