#include "workflow/run/run_dir.hpp"

#include <chrono>
#include <cstdio>
#include <ctime>
#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "core/files.hpp"

namespace spreadmap {

namespace {
// What is wrong with a manifest's shape, "" when nothing: the stages read it without asking again.
std::string shape_problem(const nlohmann::json &m) {
  if (!m.is_object()) return "it is not a JSON object";
  for (const char *list : {"cases", "verify_cases"}) {
    if (!m.contains(list)) continue;
    if (!m[list].is_array()) return std::string(list) + " is not a list";
    for (const auto &c : m[list])
      if (!c.is_object() || !c.contains("id") || !c["id"].is_string())
        return std::string("an entry of ") + list + " is not an object with a text id";
  }
  for (const char *object : {"stages", "design", "workflow", "plugins"})
    if (m.contains(object) && !m[object].is_object()) return std::string(object) + " is not an object";
  return "";
}
}  // namespace

RunDirectory::RunDirectory(fs::path root) : root_(std::move(root)) {
  fs::create_directories(root_);
  const fs::path m = root_ / "manifest.json";
  if (fs::exists(m)) {
    try {
      manifest_ = nlohmann::json::parse(read_text(m));
    } catch (const nlohmann::json::exception &e) {
      throw RunFailure(m.string() + " is damaged (" + e.what() + "): remove it, or use --force");
    }
    if (const std::string problem = shape_problem(manifest_); !problem.empty())
      throw RunFailure(m.string() + ": not a spreadmap run manifest (" + problem +
                       "): move it away to start this run directory afresh, or give the run another --out");
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
