// The whole text of a file (CSV tables, model files); files are written with core's write_atomic.
#pragma once
#include <string>

namespace spreadmap::analysis {

// Throws std::runtime_error naming the path when the file cannot be read.
std::string read_file(const std::string &path);

}  // namespace spreadmap::analysis
