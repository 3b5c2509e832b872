// Errors inside the host: exceptions with an exit code, caught once in main and printed once.
// A message says what went wrong and how to fix it, without a prefix: it is also embedded in other
// messages and warnings. printed() puts "error: " before each message, the one place that does.
#pragma once
#include <exception>
#include <stdexcept>
#include <string>
#include <vector>

namespace spreadmap {

enum ExitCode : int {
  exit_ok = 0,
  exit_failure = 1,       // a run failed (unstable case, I/O error)
  exit_input = 2,         // bad workflow, parameter, file or command line
  exit_plugin = 3,        // a plugin could not be loaded or refused its parameters
  exit_interrupted = 130  // SIGINT / SIGTERM: stopped cleanly, resumable
};

struct Error : std::runtime_error {
  Error(const std::string &what, int code) : std::runtime_error(what), messages{what}, exit_code(code) {}
  // Several messages at once (every mistake of one file), then a note that is not an error itself.
  Error(const std::vector<std::string> &all, const std::string &note, int code);
  std::vector<std::string> messages;
  std::string note;
  int exit_code;
};
struct InputError : Error {
  explicit InputError(const std::string &what) : Error(what, exit_input) {}
  InputError(const std::vector<std::string> &all, const std::string &note) : Error(all, note, exit_input) {}
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

// The text printed for an error: "error: " and the message, once per message, each ending a line
// (an Interrupted, a stop asked for, without the prefix).
std::string printed(const std::exception &e);

}  // namespace spreadmap
