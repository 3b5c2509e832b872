#include "csv_line.hpp"

#include <algorithm>
#include <stdexcept>

namespace spreadmap::core {

namespace {

bool blank(char c) { return c == ' ' || c == '\t' || c == '\r'; }

std::string_view trimmed(std::string_view s) {
  while (!s.empty() && blank(s.front())) s.remove_prefix(1);
  while (!s.empty() && blank(s.back())) s.remove_suffix(1);
  return s;
}

}  // namespace

std::vector<CsvCell> split_csv_line(std::string_view line, const std::string &where) {
  std::vector<CsvCell> out;
  std::size_t i = 0;
  while (true) {
    while (i < line.size() && blank(line[i])) ++i;
    CsvCell cell{{}, i + 1};
    if (i < line.size() && line[i] == '"') {
      bool closed = false;
      for (++i; i < line.size(); ++i) {
        if (line[i] != '"') {
          cell.text += line[i];
        } else if (i + 1 < line.size() && line[i + 1] == '"') {
          cell.text += '"';
          ++i;
        } else {
          closed = true;
          ++i;
          break;
        }
      }
      if (!closed) throw std::runtime_error(where + ":" + std::to_string(cell.column) + ": unterminated quoted field");
      while (i < line.size() && line[i] != ',') ++i;  // anything after the closing quote is dropped
    } else {
      const std::size_t end = std::min(line.find(',', i), line.size());
      cell.text = std::string(trimmed(line.substr(i, end - i)));
      i = end;
    }
    out.push_back(std::move(cell));
    if (i >= line.size()) break;
    ++i;  // the comma
  }
  return out;
}

}  // namespace spreadmap::core
