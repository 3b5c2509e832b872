#include "core/files.hpp"

#include <unistd.h>

#include <atomic>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "core/error.hpp"

namespace spreadmap {

fs::path temporary_beside(const fs::path &path) {
  static std::atomic<unsigned> counter{0};
  return path.parent_path() / ("." + path.filename().string() + ".tmp" + std::to_string(::getpid()) + "_" +
                               std::to_string(counter++) + path.extension().string());
}

void write_atomic_with(const fs::path &path, const std::function<void(const fs::path &)> &write) {
  if (path.has_parent_path()) fs::create_directories(path.parent_path());
  const fs::path tmp = temporary_beside(path);
  try {
    write(tmp);
    fs::rename(tmp, path);
  } catch (...) {
    std::error_code ec;
    fs::remove(tmp, ec);
    throw;
  }
}

void write_atomic(const fs::path &path, const std::string &content) {
  write_atomic_with(path, [&](const fs::path &tmp) {
    std::FILE *f = std::fopen(tmp.c_str(), "wb");
    if (!f) throw RunFailure("cannot write " + tmp.string() + ": check that the folder is writable");
    const bool ok = std::fwrite(content.data(), 1, content.size(), f) == content.size();
    const bool flushed = std::fflush(f) == 0 && ::fsync(fileno(f)) == 0;
    std::fclose(f);
    if (!ok || !flushed) throw RunFailure("cannot write " + path.string() + ": disk full?");
  });
}

std::string read_text(const fs::path &path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError("error: cannot read " + path.string() + ": no such file or not readable");
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string stable_hash(const std::string &text) {
  std::uint64_t h = 1469598103934665603ull;
  for (unsigned char c : text) h = (h ^ c) * 1099511628211ull;
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
  return buf;
}

}  // namespace spreadmap
