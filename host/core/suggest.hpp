// "Did you mean" for keys, plugin names and enum choices.
#pragma once
#include <string>
#include <vector>

namespace spreadmap {

// Edit distance, case-insensitive.
std::size_t edit_distance(const std::string &a, const std::string &b);
// The closest candidate within a sensible distance, or "" when none is close.
std::string closest(const std::string &word, const std::vector<std::string> &candidates);
// "a, b, c"
std::string join(const std::vector<std::string> &items, const std::string &sep = ", ");
// "a,,b" split at ',' -> {"a", "", "b"}: every item, empty ones kept ("" -> {""}).
std::vector<std::string> split(const std::string &text, char sep);
bool iequals(const std::string &a, const std::string &b);
std::string lower(std::string s);

}  // namespace spreadmap
