// What the cluster tests share: the reduced quickstart, fresh run folders, mpirun command lines,
// and the identity of a written file (a rewrite through a temporary name changes its inode).
#pragma once
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "workflow/process.hpp"

namespace spreadmap::test {

inline fs::path mini_quickstart() { return fs::path(SPREADMAP_SOURCE_DIR) / "tests/cluster/data/mini_quickstart.yaml"; }
constexpr int mini_cases = 4;

inline std::string slurp(const fs::path &p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// A new empty folder under /tmp named after the test and this process; removed by the destructor.
struct Scratch {
  fs::path dir;
  explicit Scratch(const std::string &name)
      : dir(fs::temp_directory_path() / ("spreadmap_cluster_" + name + "_" + std::to_string(::getpid()))) {
    fs::remove_all(dir);
    fs::create_directories(dir);
  }
  ~Scratch() {
    std::error_code ec;
    fs::remove_all(dir, ec);
  }
};

inline std::string case_id(int i) {
  char buf[16];  // room for any int, so that the compiler sees no truncation
  std::snprintf(buf, sizeof buf, "c%03d", i);
  return buf;
}

inline bool finished(const fs::path &case_dir) {
  if (!fs::exists(case_dir / "case.json") || !fs::exists(case_dir / "state.vtp")) return false;
  return nlohmann::json::parse(slurp(case_dir / "case.json")).value("status", "") == "done";
}

inline nlohmann::json manifest(const fs::path &run) { return nlohmann::json::parse(slurp(run / "manifest.json")); }

// `spreadmap ARGS` under mpirun with n ranks: as root too, more ranks than cores, OpenMP free to use
// any core (mpirun binds each rank to one core by default).
inline Command under_mpirun(int n, std::vector<std::string> args) {
  Command c;
  c.program = SPREADMAP_MPIEXEC;
  c.args = {"--allow-run-as-root", "--oversubscribe",          "--bind-to", "none", "-n",
            std::to_string(n),     spreadmap_binary().string()};
  c.args.insert(c.args.end(), args.begin(), args.end());
  return c;
}

// The serial run the distributed ones must match.
inline Outcome serial_run(const fs::path &out) {
  return run({{"run", mini_quickstart().string(), "--out", out.string()}, {}, {}, {}});
}

struct FileId {
  ino_t inode = 0;
  std::int64_t mtime_ns = 0;
  std::string content;
  bool operator==(const FileId &) const = default;
};

inline void PrintTo(const FileId &f, std::ostream *os) {
  *os << "{inode " << f.inode << ", mtime " << f.mtime_ns << " ns, " << f.content.size() << " bytes}";
}

inline FileId identify(const fs::path &p) {
  struct stat st {};
  if (::stat(p.c_str(), &st) != 0) return {};
  return {st.st_ino, std::int64_t(st.st_mtim.tv_sec) * 1000000000 + st.st_mtim.tv_nsec, slurp(p)};
}

inline bool contains(const std::string &text, const std::string &part) { return text.find(part) != std::string::npos; }

inline std::size_t count(const std::string &text, const std::string &part) {
  std::size_t n = 0;
  for (auto at = text.find(part); at != std::string::npos; at = text.find(part, at + part.size())) ++n;
  return n;
}

}  // namespace spreadmap::test
