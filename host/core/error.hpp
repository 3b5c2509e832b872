// Errors inside the host: exceptions with an exit code, caught once in main and printed once.
#pragma once
#include <stdexcept>
#include <string>

namespace spreadmap {

enum ExitCode : int {
  exit_ok = 0,
  exit_failure = 1,       // a run failed (unstable case, I/O error)
  exit_input = 2,         // bad workflow, parameter, file or command line
  exit_plugin = 3,        // a plugin could not be loaded or refused its parameters
  exit_interrupted = 130  // SIGINT / SIGTERM: stopped cleanly, resumable
};

struct Error : std::runtime_error {
  Error(const std::string &what, int code) : std::runtime_error(what), exit_code(code) {}
  int exit_code;
};
struct InputError : Error {
  explicit InputError(const std::string &what) : Error(what, exit_input) {}
};
struct PluginError : Error {
  explicit PluginError(const std::string &what) : Error(what, exit_plugin) {}
};
struct RunFailure : Error {
  explicit RunFailure(const std::string &what) : Error(what, exit_failure) {}
};
struct Interrupted : Error {
  explicit Interrupted(const std::string &what) : Error(what, exit_interrupted) {}
};

}  // namespace spreadmap
