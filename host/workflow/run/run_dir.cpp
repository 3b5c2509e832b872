#include "workflow/run/run_dir.hpp"

#include <chrono>
#include <cstdio>
#include <ctime>

#include "core/error.hpp"
#include "core/files.hpp"

namespace spreadmap {

RunDirectory::RunDirectory(fs::path root) : root_(std::move(root)) {
  fs::create_directories(root_);
  const fs::path m = root_ / "manifest.json";
  if (fs::exists(m)) {
    try {
      manifest_ = nlohmann::json::parse(read_text(m));
    } catch (const nlohmann::json::exception &e) {
      throw RunFailure("error: " + m.string() + " is damaged (" + e.what() + "): remove it, or use --force");
    }
  } else {
    manifest_ = {{"format", "spreadmap-run"}, {"version", 1}};
  }
}

void RunDirectory::save_locked() { write_atomic(root_ / "manifest.json", manifest_.dump(2) + "\n"); }

std::string RunDirectory::case_id(std::size_t index) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "c%03zu", index);
  return buf;
}

std::string RunDirectory::now_iso() {
  const std::time_t t = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

}  // namespace spreadmap
