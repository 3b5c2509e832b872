#include "workflow/spreading/csv_columns.hpp"

#include <stdexcept>

#include "core/suggest.hpp"
#include "core/units.hpp"

namespace spreadmap {
namespace {

std::string trim(const std::string &s) {
  const auto b = s.find_first_not_of(" \t"), e = s.find_last_not_of(" \t");
  return b == std::string::npos ? std::string() : s.substr(b, e - b + 1);
}

bool is_bare_number(const std::string &text) {
  try {
    return !parse_quantity(text).has_unit;
  } catch (const std::invalid_argument &) {
    return false;
  }
}

}  // namespace

std::pair<std::string, std::string> column_name_and_unit(const std::string &header) {
  const auto open = header.find_first_of("[(");
  if (open == std::string::npos) return {lower(trim(header)), ""};
  const auto close = header.find_first_of("])", open);
  return {lower(trim(header.substr(0, open))),
          trim(header.substr(open + 1, close == std::string::npos ? std::string::npos : close - open - 1))};
}

std::string with_column_unit(const std::string &text, const std::string &unit) {
  return !unit.empty() && is_bare_number(text) ? text + " " + unit : text;
}

}  // namespace spreadmap
