#include "read_file.hpp"

#include <fstream>
#include <sstream>
#include <stdexcept>

namespace spreadmap::analysis {

std::string read_file(const std::string &path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read " + path + ": no such file or no permission");
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace spreadmap::analysis
