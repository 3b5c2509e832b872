// Error messages for user input, in one shape: "FILE:LINE:COL: key.path: what\n  hint" (printed after
// "error: ", core/error.hpp).
// Validation collects every problem of a file before stopping, so a user fixes them in one go.
#pragma once
#include "core/yaml_fwd.hpp"

#include <string>
#include <vector>

namespace spreadmap {

struct Location {
  std::string file;
  int line = 0, column = 0;  // 1-based; 0 = unknown
  static Location of(const std::string &file, const YAML::Node &node);
  std::string str() const;
};

class Diagnostics {
 public:
  void error(const Location &where, const std::string &key_path, const std::string &what, const std::string &hint = "");
  void error(const std::string &text) { errors_.push_back(text); }
  bool empty() const { return errors_.empty(); }
  const std::vector<std::string> &errors() const { return errors_; }
  // Throws InputError with all messages when any was recorded.
  void throw_if_any() const;

 private:
  std::vector<std::string> errors_;
};

}  // namespace spreadmap
