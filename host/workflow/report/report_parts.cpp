#include "workflow/report/report_parts.hpp"

#include "core/units.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <cmath>
#include <map>
#include <nlohmann/json.hpp>

#include "core/files.hpp"
#include "workflow/map/mapping.hpp"
#include "workflow/report/html.hpp"
#include "analysis/known_columns.hpp"

namespace spreadmap::report {

using nlohmann::json;

json read_json(const fs::path &p) {
  if (!fs::exists(p)) return json();
  try {
    return json::parse(read_text(p));
  } catch (const std::exception &e) {
    spdlog::warn("report: {} not read ({}); its part of the report is left out", p.string(), e.what());
    return json();
  }
}

const json &member(const json &j, const char *key) {
  static const json none = json::object();
  if (!j.is_object()) return none;
  const auto it = j.find(key);
  return it == j.end() ? none : *it;
}

std::optional<analysis::Table> read_table(const fs::path &p) {
  if (!fs::exists(p)) return std::nullopt;
  try {
    return analysis::Table::read_csv(p.string());
  } catch (const std::exception &e) {
    spdlog::warn("report: {} not read ({}); its part of the report is left out", p.string(), e.what());
    return std::nullopt;
  }
}

std::string shown(const json &v, const std::string &unit) {
  if (v.is_number()) return display(v.get<double>(), unit);
  if (v.is_string()) return v.get<std::string>();
  if (v.is_null()) return "";
  return v.dump();
}

std::string unit_of(const std::string &name, const json &units) {
  if (units.is_object() && units.contains(name) && units[name].is_string()) return units[name].get<std::string>();
  return known_unit(name);
}

std::string number(double v, const char *format) { return std::isfinite(v) ? fmt::format(fmt::runtime(format), v) : "–"; }

double field(const json &j, const char *key) {
  return j.is_object() && j.contains(key) && j[key].is_number() ? j[key].get<double>() : std::nan("");
}

std::string paragraph(const std::string &text) { return "<p>" + html::escape(text) + "</p>\n"; }

std::string warning(const std::string &text) { return "<p class=\"warn\">" + html::escape(text) + "</p>\n"; }

std::string figure(const fs::path &png, const std::string &caption, const std::string &css_class) {
  const std::string img = html::inline_png(png, caption, css_class);
  if (img.empty()) return "";
  return "<figure>" + img + "<figcaption>" + html::escape(caption) + "</figcaption></figure>\n";
}

std::string metric_label(const std::string &name) { return known_symbol(name); }

}  // namespace spreadmap::report
