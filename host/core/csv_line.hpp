#pragma once
// One CSV line split into cells: the one splitter behind the analysis tables (metrics.csv, design
// files) and the engine's particle files.

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace spreadmap::core {

struct CsvCell {
  std::string text;     // trimmed of spaces and tabs; a quoted cell unquoted ("" is one quote)
  std::size_t column;   // 1-based character position where the cell starts (after leading blanks)
};

// Splits at commas outside quotes. An unterminated quote throws std::runtime_error
// "<where>:<column>: unterminated quoted field".
std::vector<CsvCell> split_csv_line(std::string_view line, const std::string &where);

}  // namespace spreadmap::core
