// A stage's settings after the schema check (StageEntry::settings). Every key of the stage's schema
// is there: the value given, or the schema's default where none was given or the one given was
// refused (the run stops on that error; validate() goes on to find the others), so a default is
// written once, in the schema. A required key that was refused reads as 0, false or "".
// The schema builders (number, integer, table, ...) come with <spreadmap/params.hpp>.
#pragma once
#include <spreadmap/params.hpp>

#include <cstddef>
#include <nlohmann/json_fwd.hpp>
#include <string>

#include "core/schema.hpp"

namespace spreadmap {

double setting_number(const nlohmann::json &settings, const char *key);
std::size_t setting_count(const nlohmann::json &settings, const char *key);
bool setting_flag(const nlohmann::json &settings, const char *key);
std::string setting_text(const nlohmann::json &settings, const char *key);

}  // namespace spreadmap
