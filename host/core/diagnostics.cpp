#include "core/diagnostics.hpp"

#include "core/error.hpp"

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
  std::string text = "error: " + where.str() + ": " + (key_path.empty() ? "" : key_path + ": ") + what;
  if (!hint.empty()) text += "\n  " + hint;
  errors_.push_back(text);
}

void Diagnostics::throw_if_any() const {
  if (errors_.empty()) return;
  std::string all;
  for (const auto &e : errors_) all += (all.empty() ? "" : "\n") + e;
  throw InputError(all);
}

}  // namespace spreadmap
