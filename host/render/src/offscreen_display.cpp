#include "offscreen_display.hpp"

#include <spreadmap/render/figures.hpp>

#include <cerrno>
#include <chrono>
#include <algorithm>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <mutex>
#include <optional>
#include <string>

#include <fcntl.h>
#include <poll.h>
#include <sys/prctl.h>
#include <sys/syscall.h>
#include <sys/wait.h>
#include <unistd.h>

namespace sm = spreadmap;

namespace {

// Large enough for any figure we make; the render window draws into an off-screen framebuffer,
// the screen only has to exist.
constexpr const char* screen_geometry = "3840x2400x24";
constexpr int start_timeout_ms = 20000;

std::optional<std::string> find_on_path(const std::string& name) {
  const char* path = std::getenv("PATH");
  std::string dirs = path ? path : "/usr/local/bin:/usr/bin:/bin";
  std::size_t start = 0;
  while (start <= dirs.size()) {
    const std::size_t end = std::min(dirs.find(':', start), dirs.size());
    const std::filesystem::path candidate = std::filesystem::path(dirs.substr(start, end - start)) / name;
    if (::access(candidate.c_str(), X_OK) == 0) return candidate.string();
    start = end + 1;
  }
  return std::nullopt;
}

// Owns the Xvfb child: stopped (SIGTERM, then reaped) when the process exits normally.
class PrivateXvfb {
 public:
  static PrivateXvfb& instance() {
    static PrivateXvfb server;
    return server;
  }
  ~PrivateXvfb() { stop(); }

  std::string start() {
    const auto exe = find_on_path("Xvfb");
    if (!exe)
      throw sm::render::RenderError(
          "render: DISPLAY is unset and Xvfb was not found on PATH; VTK 9.1 on Debian renders only "
          "through X. Install the Debian package 'xvfb' (apt-get install xvfb) or set DISPLAY");
    int fds[2];
    if (::pipe2(fds, O_CLOEXEC) != 0)
      throw sm::render::RenderError(std::string("render: cannot create a pipe for Xvfb: ") + std::strerror(errno));
    const bool on_main_thread = ::syscall(SYS_gettid) == ::getpid();
    const pid_t parent = ::getpid();
    const pid_t child = ::fork();
    if (child < 0) {
      ::close(fds[0]);
      ::close(fds[1]);
      throw sm::render::RenderError(std::string("render: cannot fork Xvfb: ") + std::strerror(errno));
    }
    if (child == 0) {
      // The server must not outlive a crashed parent. PDEATHSIG fires when the creating *thread*
      // ends, so use it only when that thread is the main one; otherwise rely on the destructor.
      if (on_main_thread) ::prctl(PR_SET_PDEATHSIG, SIGTERM);
      if (::getppid() != parent) ::_exit(1);
      ::dup2(fds[1], 3);  // -displayfd 3: the write end, without O_CLOEXEC after dup2
      const int devnull = ::open("/dev/null", O_RDWR);
      if (devnull >= 0) {
        ::dup2(devnull, 0);
        ::dup2(devnull, 1);
        ::dup2(devnull, 2);
      }
      ::setsid();  // own process group: terminal signals aimed at the parent's group miss it
      // -noreset: by default the server resets when its last client disconnects, and a client that
      // connects during the reset (VTK opens and closes several connections per figure) is dropped
      // after connect(): "bad X server connection". Two renders in parallel slow the reset enough
      // to hit it in 1 run in 5; with -noreset, 0 in 100.
      ::execl(exe->c_str(), "Xvfb", "-displayfd", "3", "-screen", "0", screen_geometry, "-nolisten", "tcp", "-noreset",
              static_cast<char*>(nullptr));
      ::_exit(127);
    }
    ::close(fds[1]);
    pid_ = child;
    std::string number;
    const auto deadline_left = [start = std::chrono::steady_clock::now()] {
      return start_timeout_ms - static_cast<int>(std::chrono::duration_cast<std::chrono::milliseconds>(
                                                     std::chrono::steady_clock::now() - start)
                                                     .count());
    };
    for (;;) {
      pollfd p{fds[0], POLLIN, 0};
      const int left = deadline_left();
      if (left <= 0 || ::poll(&p, 1, left) <= 0) break;
      char c;
      const ssize_t n = ::read(fds[0], &c, 1);
      if (n <= 0 || c == '\n') break;
      number.push_back(c);
    }
    ::close(fds[0]);
    if (number.empty()) {
      stop();
      throw sm::render::RenderError("render: the private Xvfb (" + *exe + ") did not report a display within " +
                                    std::to_string(start_timeout_ms / 1000) + " s; check that it runs (" + *exe +
                                    " -displayfd 1) or set DISPLAY");
    }
    display_ = ":" + number;
    ::setenv("DISPLAY", display_.c_str(), 1);
    return display_;
  }

  bool running() const { return pid_ > 0; }
  const std::string& display() const { return display_; }

 private:
  void stop() {
    if (pid_ <= 0) return;
    ::kill(pid_, SIGTERM);
    int status = 0;
    for (int i = 0; i < 200; ++i) {  // up to 2 s, then force
      if (::waitpid(pid_, &status, WNOHANG) == pid_) {
        pid_ = -1;
        break;
      }
      ::usleep(10000);
    }
    if (pid_ > 0) {
      ::kill(pid_, SIGKILL);
      ::waitpid(pid_, &status, 0);
      pid_ = -1;
    }
    if (!display_.empty()) {
      const char* now = std::getenv("DISPLAY");
      if (now && display_ == now) ::unsetenv("DISPLAY");
    }
  }

  pid_t pid_ = -1;
  std::string display_;
};

std::mutex display_mutex;

}  // namespace

namespace spreadmap::render::detail {

std::string ensure_display() {
  std::lock_guard lock(display_mutex);
  auto& server = PrivateXvfb::instance();
  if (server.running()) return server.display();
  const char* display = std::getenv("DISPLAY");
  if (display && *display) return display;
  return server.start();
}

bool owns_private_display() {
  std::lock_guard lock(display_mutex);
  return PrivateXvfb::instance().running();
}

}  // namespace spreadmap::render::detail
