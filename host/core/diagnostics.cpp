#include "core/diagnostics.hpp"

#include "core/error.hpp"

#include <algorithm>
#include <yaml-cpp/yaml.h>

namespace spreadmap {

Location Location::of(const std::string &file, const YAML::Node &node) {
  Location l{file};
  if (node.IsDefined() && node.Mark().line >= 0) {
    l.line = node.Mark().line + 1;  // yaml-cpp marks are 0-based
    l.column = node.Mark().column + 1;
  }
  return l;
}

std::string Location::str() const {
  if (line <= 0) return file;
  if (column <= 0) return file + ":" + std::to_string(line);  // a CSV row
  return file + ":" + std::to_string(line) + ":" + std::to_string(column);
}

void Diagnostics::error(const Location &where, const std::string &key_path, const std::string &what,
                        const std::string &hint) {
  std::string text = where.str() + ": " + (key_path.empty() ? "" : key_path + ": ") + what;
  if (!hint.empty()) text += "\n  " + hint;
  errors_.push_back(text);
}

// The first `shown` messages, then "... and N more errors": a file of thousands of mistakes is fixed
// from its first ones, not from a flood. All are kept (errors()): callers count them to see new ones.
void Diagnostics::throw_if_any() const {
  if (errors_.empty()) return;
  constexpr std::size_t shown = 50;
  const std::vector<std::string> first(errors_.begin(), errors_.begin() + std::min(errors_.size(), shown));
  throw InputError(first, errors_.size() > shown ? "... and " + std::to_string(errors_.size() - shown) +
                                                       " more errors (fix these and run again to see them)"
                                                 : "");
}

}  // namespace spreadmap
