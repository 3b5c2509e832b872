// A stage's settings after the schema check (StageEntry::settings): each read with the value to use
// where the check refused the one given (the run stops on that error; validate() goes on to find
// the others). The schema builders (number, integer, table, ...) come with <spreadmap/params.hpp>.
#pragma once
#include <spreadmap/params.hpp>

#include <cstddef>
#include <nlohmann/json.hpp>
#include <string>

#include "core/schema.hpp"

namespace spreadmap {

double setting_number(const nlohmann::json &settings, const char *key, double fallback);
std::size_t setting_count(const nlohmann::json &settings, const char *key, std::size_t fallback);
bool setting_flag(const nlohmann::json &settings, const char *key, bool fallback);
std::string setting_text(const nlohmann::json &settings, const char *key, const std::string &fallback = "");

}  // namespace spreadmap
