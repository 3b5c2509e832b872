// Reading what a run wrote, for the tests that run the binary: a file's bytes, a JSON file, a CSV
// table by column (spreadmap's CSVs never quote: no cell holds a comma); a fresh run directory.
#pragma once
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

namespace spreadmap::test {

inline std::string slurp(const std::filesystem::path &p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

inline nlohmann::json json_file(const std::filesystem::path &p) { return nlohmann::json::parse(slurp(p)); }

// header -> the column's cells, top to bottom
inline std::map<std::string, std::vector<std::string>> csv_columns(const std::filesystem::path &p) {
  std::istringstream in(slurp(p));
  std::string line;
  std::getline(in, line);
  std::vector<std::string> names;
  std::map<std::string, std::vector<std::string>> cols;
  for (std::istringstream h(line); std::getline(h, line, ',');) names.push_back(line);
  while (std::getline(in, line)) {
    std::istringstream row(line);
    std::string cell;
    for (const auto &n : names) {
      if (!std::getline(row, cell, ',')) cell.clear();
      cols[n].push_back(cell);
    }
  }
  return cols;
}

// An empty folder for a run, <temp>/<stem>_<pid>.
inline std::filesystem::path fresh_run_directory(const std::string &stem) {
  const auto dir = std::filesystem::temp_directory_path() / (stem + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  return dir;
}

inline bool contains(const std::string &text, const std::string &part) { return text.find(part) != std::string::npos; }

}  // namespace spreadmap::test
