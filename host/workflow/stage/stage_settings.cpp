#include "workflow/stage/stage_settings.hpp"
#include <nlohmann/json.hpp>

namespace spreadmap {

double setting_number(const nlohmann::json &settings, const char *key) {
  const auto it = settings.find(key);
  return it != settings.end() && it->is_number() ? it->get<double>() : 0.0;
}

std::size_t setting_count(const nlohmann::json &settings, const char *key) {
  const auto it = settings.find(key);
  return it != settings.end() && it->is_number_integer() && it->get<long>() >= 0 ? it->get<std::size_t>() : 0;
}

bool setting_flag(const nlohmann::json &settings, const char *key) {
  const auto it = settings.find(key);
  return it != settings.end() && it->is_boolean() && it->get<bool>();
}

std::string setting_text(const nlohmann::json &settings, const char *key) {
  const auto it = settings.find(key);
  return it != settings.end() && it->is_string() ? it->get<std::string>() : std::string();
}

}  // namespace spreadmap
