// A warning said once per process: a run resolves its scene once per stage, and the same warning
// each time would read as many problems.
#pragma once
#include <spdlog/spdlog.h>

#include <mutex>
#include <set>
#include <string>

namespace spreadmap {

inline void warn_once(const std::string &text) {
  static std::mutex guard;
  static std::set<std::string> said;
  const std::lock_guard<std::mutex> lock(guard);
  if (said.insert(text).second) spdlog::warn("{}", text);
}

}  // namespace spreadmap
