// The private X server: started on demand when DISPLAY is unset, stopped when the process exits,
// and a missing Xvfb is reported with the Debian package to install. Each case runs in a forked
// child so that it sees a process that has not started a server yet.
#include "host/render/src/offscreen_display.hpp"

#include <gtest/gtest.h>

#include <spreadmap/render/figures.hpp>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <thread>

#include <sys/wait.h>
#include <unistd.h>

namespace r = spreadmap::render;
namespace fs = std::filesystem;

namespace {
// Runs `body` in a child; its exit status (0 = pass) and what it wrote to `out` come back.
template <class F> std::pair<int, std::string> in_child(F body) {
  int fds[2];
  if (::pipe(fds) != 0) return {-1, ""};
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::close(fds[0]);
    std::string out;
    const int code = body(out);
    if (!out.empty() && ::write(fds[1], out.data(), out.size()) < 0) std::_Exit(99);
    ::close(fds[1]);
    std::exit(code);  // std::exit runs static destructors: the server must stop here
  }
  ::close(fds[1]);
  std::string out;
  char buf[256];
  ssize_t n;
  while ((n = ::read(fds[0], buf, sizeof buf)) > 0) out.append(buf, static_cast<std::size_t>(n));
  ::close(fds[0]);
  int status = 0;
  ::waitpid(pid, &status, 0);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, out};
}
}  // namespace

TEST(RenderDisplay, MissingXvfbNamesTheDebianPackage) {
  const auto [code, message] = in_child([](std::string& out) {
    ::unsetenv("DISPLAY");
    ::setenv("PATH", "/nonexistent-spreadmap-dir", 1);
    try {
      r::detail::ensure_display();
      out = "no error";
      return 1;
    } catch (const r::RenderError& e) {
      out = e.what();
      return 0;
    }
  });
  EXPECT_EQ(code, 0) << message;
  EXPECT_NE(message.find("'xvfb'"), std::string::npos) << message;
  EXPECT_NE(message.find("DISPLAY"), std::string::npos) << message;
}

TEST(RenderDisplay, StartsAPrivateServerAndStopsItAtExit) {
  const auto [code, display] = in_child([](std::string& out) {
    ::unsetenv("DISPLAY");
    out = r::detail::ensure_display();
    const char* env = std::getenv("DISPLAY");
    const bool ok = env && out == env && r::detail::owns_private_display() && r::detail::ensure_display() == out;
    return ok ? 0 : 1;  // a second call reuses the same server
  });
  ASSERT_EQ(code, 0) << display;
  ASSERT_GT(display.size(), 1u);
  ASSERT_EQ(display[0], ':');
  // Xvfb removes its socket when it terminates: the child's exit must have stopped it.
  const fs::path socket = "/tmp/.X11-unix/X" + display.substr(1);
  for (int i = 0; i < 100 && fs::exists(socket); ++i) std::this_thread::sleep_for(std::chrono::milliseconds(20));
  EXPECT_FALSE(fs::exists(socket)) << "the private Xvfb on " << display << " outlived its process";
}

TEST(RenderDisplay, AnExistingDisplayIsUsedAsIs) {
  const auto [code, display] = in_child([](std::string& out) {
    ::setenv("DISPLAY", ":4242", 1);
    out = r::detail::ensure_display();
    return r::detail::owns_private_display() ? 1 : 0;
  });
  EXPECT_EQ(code, 0);
  EXPECT_EQ(display, ":4242");
}
