// Writes a whole file or nothing: the text goes to "<path>.tmp.<pid>" and is renamed over path,
// so a crash never leaves half a file (DESIGN.md, run directory).
#pragma once
#include <string>

namespace spreadmap::analysis {

// Throws std::runtime_error naming the path when the file cannot be written.
void write_file_atomically(const std::string &path, const std::string &text);
std::string read_file(const std::string &path);

}  // namespace spreadmap::analysis
