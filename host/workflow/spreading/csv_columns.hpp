// Columns of the CSV files a scene names (a size table, a height map): a header may give a
// column's unit in brackets, "from [um]", for the bare numbers below it.
#pragma once
#include <string>
#include <utility>

namespace spreadmap {

// "From [um]" -> {"from", "um"}, "fraction" -> {"fraction", ""}: the name in lower case, the unit as written.
std::pair<std::string, std::string> column_name_and_unit(const std::string &header);

// A cell's text with the column's unit added when the cell is a bare number ("20" under "[um]" ->
// "20 um"); otherwise as written (a cell may carry its own unit).
std::string with_column_unit(const std::string &text, const std::string &unit);

}  // namespace spreadmap
