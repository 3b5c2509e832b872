#include "workflow/stage/stage_settings.hpp"

namespace spreadmap {

double setting_number(const nlohmann::json &settings, const char *key, double fallback) {
  const auto it = settings.find(key);
  return it != settings.end() && it->is_number() ? it->get<double>() : fallback;
}

std::size_t setting_count(const nlohmann::json &settings, const char *key, std::size_t fallback) {
  const auto it = settings.find(key);
  return it != settings.end() && it->is_number_integer() && it->get<long>() >= 0 ? it->get<std::size_t>() : fallback;
}

bool setting_flag(const nlohmann::json &settings, const char *key, bool fallback) {
  const auto it = settings.find(key);
  return it != settings.end() && it->is_boolean() ? it->get<bool>() : fallback;
}

std::string setting_text(const nlohmann::json &settings, const char *key, const std::string &fallback) {
  const auto it = settings.find(key);
  return it != settings.end() && it->is_string() ? it->get<std::string>() : fallback;
}

}  // namespace spreadmap
