#include "workflow/run/run_lock.hpp"

#include <fcntl.h>
#include <spdlog/spdlog.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstring>
#include <sstream>
#include <string>

#include "core/error.hpp"

namespace spreadmap {

namespace {

struct Holder {
  std::string host;
  long pid = 0;
};

std::string this_host() {
  char name[256] = {};
  if (::gethostname(name, sizeof name - 1) != 0) return "unknown-host";
  return name;
}

// What the lock file says: "<host> <pid>"; empty when it says nothing readable.
Holder read_holder(int fd) {
  char buf[512] = {};
  const ssize_t n = ::pread(fd, buf, sizeof buf - 1, 0);
  Holder h;
  if (n > 0) std::istringstream(std::string(buf, std::size_t(n))) >> h.host >> h.pid;
  return h;
}

void write_holder(int fd) {
  const std::string text = this_host() + " " + std::to_string(::getpid()) + "\n";
  // advisory text for the next reader: a failure here leaves the lock itself intact
  if (::ftruncate(fd, 0) != 0 || ::pwrite(fd, text.data(), text.size(), 0) != ssize_t(text.size()))
    spdlog::debug("could not write the holder into the run lock: {}", std::strerror(errno));
}

// The run directory as the user named it (--out, else runs/<name>), or an error saying why not.
void create_run_folder(const std::filesystem::path &root) {
  std::error_code ec;
  if (std::filesystem::exists(root, ec) && !std::filesystem::is_directory(root, ec))
    throw InputError("--out " + root.string() +
                     ": is a file, not a folder; give a new folder or an earlier run's directory");
  std::filesystem::create_directories(root, ec);
  if (ec)
    throw InputError("--out " + root.string() + ": cannot create the folder (" + ec.message() +
                     "); give a folder in a place you can write to");
}

bool exited_here(const Holder &h) {
  return h.pid > 0 && h.pid != ::getpid() && h.host == this_host() && ::kill(pid_t(h.pid), 0) != 0 &&
         errno == ESRCH;
}

}  // namespace

RunLock::RunLock(const std::filesystem::path &dir, Mode mode) {
  create_run_folder(dir);
  const std::filesystem::path file = dir / ".lock";
  // close-on-exec: a child (Xvfb, sbatch) must not keep the lock past this process
  fd_ = ::open(file.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd_ < 0)
    throw RunFailure(file.string() + ": cannot open the run directory's lock (" + std::strerror(errno) +
                     "); check the folder's permissions, or use another --out");
  const int op = (mode == Mode::exclusive ? LOCK_EX : LOCK_SH) | LOCK_NB;
  if (::flock(fd_, op) != 0) {
    const int err = errno;
    const Holder h = read_holder(fd_);
    ::close(fd_);
    fd_ = -1;
    if (err != EWOULDBLOCK)
      throw RunFailure(file.string() + ": cannot lock the run directory (" + std::strerror(err) +
                       "); use another --out on a local disk");
    const std::string who = h.pid > 0 ? "spreadmap pid " + std::to_string(h.pid) + " on host " + h.host
                                      : "another spreadmap";
    throw RunFailure(dir.string() + ": " + who +
                     " is writing into this run directory; wait for it to finish, or give this run "
                     "another --out");
  }
  if (const Holder h = read_holder(fd_); exited_here(h))
    spdlog::info("{}: taking over the lock of pid {}, which has exited", dir.string(), h.pid);
  write_holder(fd_);
}

RunLock::~RunLock() {
  if (fd_ >= 0) ::close(fd_);  // frees the flock
}

}  // namespace spreadmap
