// The temporaries that write_atomic would leave beside a target after a failed or interrupted
// write (".<name>.tmp-…", core/files.hpp): tests expect none.
#pragma once
#include <filesystem>
#include <string>
#include <vector>

inline std::vector<std::string> temporaries_beside(const std::filesystem::path &target) {
  const std::filesystem::path folder = target.has_parent_path() ? target.parent_path() : ".";
  const std::string prefix = "." + target.filename().string() + ".tmp";
  std::vector<std::string> out;
  for (const auto &e : std::filesystem::directory_iterator(folder))
    if (e.path().filename().string().rfind(prefix, 0) == 0) out.push_back(e.path().string());
  return out;
}
