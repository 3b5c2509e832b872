#include "workflow/process.hpp"

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <csignal>
#include <fstream>
#include <sstream>
#include <stdexcept>

extern char **environ;

namespace spreadmap::test {

namespace {

std::string slurp(const fs::path &p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

fs::path fresh_dir() {
  static std::atomic<int> counter{0};
  const fs::path d =
      fs::temp_directory_path() / ("spreadmap_child_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

}  // namespace

fs::path spreadmap_binary() { return fs::path(SPREADMAP_BINARY_DIR) / "bin" / "spreadmap"; }

std::string Outcome::describe() const {
  return (exited ? "exit " + std::to_string(exit_code) : "signal " + std::to_string(signal)) + "\n--- stderr:\n" + err +
         "--- stdout:\n" + out;
}

Child::Child(const Command &command) : dir_(fresh_dir()) {
  // Everything the child needs is prepared before fork: after it, only async-signal-safe calls.
  std::vector<std::string> args = {(command.program.empty() ? spreadmap_binary() : command.program).string()};
  args.insert(args.end(), command.args.begin(), command.args.end());
  std::map<std::string, std::string> env;
  for (char **e = environ; *e; ++e) {
    const std::string kv = *e;
    const auto eq = kv.find('=');
    if (eq != std::string::npos) env[kv.substr(0, eq)] = kv.substr(eq + 1);
  }
  for (const auto &[k, v] : command.env) env[k] = v;
  std::vector<std::string> env_text;
  for (const auto &[k, v] : env) env_text.push_back(k + "=" + v);
  std::vector<char *> argv, envp;
  for (auto &a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  for (auto &e : env_text) envp.push_back(e.data());
  envp.push_back(nullptr);
  const std::string out = (dir_ / "stdout").string(), err = (dir_ / "stderr").string();
  const std::string cwd = command.cwd.string();

  pid_ = ::fork();
  if (pid_ < 0) throw std::runtime_error("fork failed");
  if (pid_ == 0) {
    const int o = ::open(out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int r = ::open(err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int n = ::open("/dev/null", O_RDONLY);
    if (o < 0 || r < 0 || n < 0) ::_exit(120);
    ::dup2(n, 0);
    ::dup2(o, 1);
    ::dup2(r, 2);
    if (!cwd.empty() && ::chdir(cwd.c_str()) != 0) ::_exit(121);
    ::execve(argv[0], argv.data(), envp.data());
    ::_exit(122);
  }
}

Child::~Child() {
  if (!reaped_ && pid_ > 0) {
    ::kill(pid_, SIGKILL);
    int status = 0;
    ::waitpid(pid_, &status, 0);
  }
  std::error_code ec;
  fs::remove_all(dir_, ec);
}

void Child::signal(int sig) const { ::kill(pid_, sig); }

bool Child::running() {
  if (reaped_) return false;
  int status = 0;
  const pid_t r = ::waitpid(pid_, &status, WNOHANG);
  if (r == 0) return true;
  reaped_ = true;
  outcome_.exited = WIFEXITED(status);
  outcome_.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  outcome_.signal = WIFSIGNALED(status) ? WTERMSIG(status) : 0;
  return false;
}

Outcome Child::wait() {
  if (!reaped_) {
    int status = 0;
    while (::waitpid(pid_, &status, 0) < 0 && errno == EINTR) {
    }
    reaped_ = true;
    outcome_.exited = WIFEXITED(status);
    outcome_.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    outcome_.signal = WIFSIGNALED(status) ? WTERMSIG(status) : 0;
  }
  outcome_.out = slurp(dir_ / "stdout");
  outcome_.err = slurp(dir_ / "stderr");
  return outcome_;
}

Outcome run(const Command &command) { return Child(command).wait(); }

std::string crash_marker(const std::string &err) {
  for (const char *m : {"AddressSanitizer", "LeakSanitizer", "UndefinedBehaviorSanitizer",
                        "runtime error:", "terminate called", "Segmentation fault", "core dumped", "[json.exception",
                        "yaml-cpp:", "bad_any_cast", "std::bad_alloc", "basic_string"})
    if (err.find(m) != std::string::npos) return m;
  return "";
}

}  // namespace spreadmap::test
