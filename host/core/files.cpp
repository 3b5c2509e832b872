#include "core/files.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <signal.h>
#include <spreadmap/digest.hpp>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstdlib>
#include <cerrno>
#include <cstdio>
#include <fstream>
#include <random>
#include <sstream>
#include <system_error>

#include "core/error.hpp"

namespace spreadmap {

namespace {

std::error_code last_error() { return {errno, std::generic_category()}; }

// The usual fix for each way a write fails.
std::string fix_for(const std::error_code &ec) {
  if (ec == std::errc::no_space_on_device || ec == std::errc::file_too_large || ec.value() == EDQUOT)
    return "free some disk space (or raise the quota) and run again";
  if (ec == std::errc::permission_denied || ec == std::errc::operation_not_permitted ||
      ec == std::errc::read_only_file_system)
    return "make the folder writable, or write to another folder";
  if (ec == std::errc::is_a_directory || ec == std::errc::directory_not_empty)
    return "a folder has this name: move it away";
  if (ec == std::errc::not_a_directory || ec == std::errc::file_exists)
    return "a file stands where a folder of this path should be: move it away";
  return "check that the folder exists and is writable";
}

[[noreturn]] void fail(const fs::path &path, const std::string &what, const std::error_code &ec) {
  throw RunFailure("cannot write " + path.string() + ": " + what + " (" + ec.message() + ")\n  " + fix_for(ec));
}

// Drawn once per process: it separates processes with the same pid on hosts that share a folder.
std::uint32_t process_random() {
  static const std::uint32_t r = std::random_device{}();
  return r;
}

// Created exclusively (O_EXCL), so no other writer can be holding the same temporary.
fs::path create_temporary(const fs::path &path) {
  for (int attempt = 0;; ++attempt) {
    fs::path tmp = temporary_beside(path);
    const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd >= 0) {
      ::close(fd);
      return tmp;
    }
    if (errno != EEXIST || attempt == 100) fail(path, "cannot create the temporary " + tmp.string(), last_error());
  }
}

void write_all(const fs::path &path, const fs::path &tmp, std::string_view content) {
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_TRUNC | O_CLOEXEC);
  if (fd < 0) fail(path, "cannot open the temporary " + tmp.string(), last_error());
  while (!content.empty()) {
    const ssize_t n = ::write(fd, content.data(), content.size());
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      const std::error_code ec = n < 0 ? last_error() : std::make_error_code(std::errc::io_error);
      ::close(fd);
      fail(path, "writing the temporary " + tmp.string() + " stopped", ec);
    }
    content.remove_prefix(static_cast<std::size_t>(n));
  }
  if (::close(fd) != 0) fail(path, "cannot close the temporary " + tmp.string(), last_error());
}

// The content reaches the disk before the rename, so a power cut cannot leave an empty file under
// the final name.
void sync_file(const fs::path &path, const fs::path &tmp) {
  const int fd = ::open(tmp.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) fail(path, "the temporary " + tmp.string() + " is gone", last_error());
  const bool synced = ::fsync(fd) == 0;
  const std::error_code ec = last_error();
  ::close(fd);
  if (!synced) fail(path, "cannot flush the temporary " + tmp.string() + " to disk", ec);
}

// The rename reaches the disk with its folder. Best effort: the file itself is whole already, and
// some file systems refuse to sync a folder.
void sync_folder(const fs::path &path) {
  const fs::path folder = path.has_parent_path() ? path.parent_path() : fs::path(".");
  const int fd = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) return;
  (void)::fsync(fd);
  ::close(fd);
}

}  // namespace

fs::path temporary_beside(const fs::path &path) {
  static std::atomic<std::uint64_t> count{0};
  char tag[64];
  std::snprintf(tag, sizeof tag, ".tmp-%ld-%llu-%08x", static_cast<long>(::getpid()),
                static_cast<unsigned long long>(count++), static_cast<unsigned>(process_random()));
  return path.parent_path() / ("." + path.filename().string() + tag + path.extension().string());
}

// What `path` is when it exists and is no regular file ("a symbolic link", "a FIFO", ...); "" otherwise.
// A rename over it would replace the link, pipe or device itself (as root, --out /dev/stdout).
std::string not_a_regular_file(const fs::path &path) {
  struct stat st {};
  // (a folder is left to the rename, which refuses to replace one)
  if (::lstat(path.c_str(), &st) != 0 || S_ISREG(st.st_mode) || S_ISDIR(st.st_mode)) return "";
  if (S_ISLNK(st.st_mode)) return "a symbolic link";
  if (S_ISFIFO(st.st_mode)) return "a FIFO";
  if (S_ISCHR(st.st_mode) || S_ISBLK(st.st_mode)) return "a device";
  return "a socket";
}

void write_atomic_with(const fs::path &path, const std::function<void(const fs::path &)> &write) {
  if (const std::string what = not_a_regular_file(path); !what.empty())
    throw RunFailure("cannot write " + path.string() + ": it is " + what +
                     ", which spreadmap never replaces\n  give the path of a regular file, or of one that does not "
                     "exist yet");
  if (path.has_parent_path()) {
    std::error_code ec;
    fs::create_directories(path.parent_path(), ec);
    if (ec) fail(path, "cannot create its folder " + path.parent_path().string(), ec);
  }
  const fs::path tmp = create_temporary(path);
  try {
    write(tmp);
    sync_file(path, tmp);
    std::error_code ec;
    fs::rename(tmp, path, ec);
    if (ec) fail(path, "cannot rename the temporary " + tmp.string() + " over it", ec);
  } catch (...) {
    std::error_code ignored;
    fs::remove(tmp, ignored);
    throw;
  }
  sync_folder(path);
}

void write_atomic(const fs::path &path, std::string_view content) {
  write_atomic_with(path, [&](const fs::path &tmp) { write_all(path, tmp, content); });
}

std::string read_text(const fs::path &path) {
  std::error_code ec;
  // a folder opens as a stream that reads as empty: say what it is instead
  if (fs::is_directory(path, ec)) throw InputError(path.string() + " is a directory; give a file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError("cannot read " + path.string() + ": no such file or not readable");
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string stable_hash(const std::string &text) { return content_digest(text); }

}  // namespace spreadmap

namespace spreadmap {

std::size_t remove_stale_temporaries(const fs::path &folder) {
  std::size_t removed = 0;
  std::error_code ec;
  const auto now = fs::file_time_type::clock::now();
  for (auto it = fs::recursive_directory_iterator(folder, fs::directory_options::skip_permission_denied, ec);
       !ec && it != fs::recursive_directory_iterator(); it.increment(ec)) {
    const std::string name = it->path().filename().string();
    const auto tag = name.find(".tmp-");
    if (name.empty() || name[0] != '.' || tag == std::string::npos || !it->is_regular_file(ec)) continue;
    // ".<name>.tmp-<pid>-...": a writer still alive keeps its temporary; so does one written in the last
    // minute (its pid may be another host's, on a shared folder)
    const long pid = std::strtol(name.c_str() + tag + 5, nullptr, 10);
    const bool alive = pid > 0 && (::kill(static_cast<pid_t>(pid), 0) == 0 || errno == EPERM);
    if (alive || now - it->last_write_time(ec) < std::chrono::minutes(1)) continue;
    if (fs::remove(it->path(), ec)) ++removed;
  }
  return removed;
}

}  // namespace spreadmap
