// What the run report's sections share: reading the run's files (a missing or unreadable file leaves
// its section out, with a warning for the unreadable), values shown in display units, and the
// section type the page is assembled from.
#pragma once
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "analysis/table.hpp"

namespace spreadmap::report {

namespace fs = std::filesystem;

struct PageSection {
  std::string id, title, body;  // empty body: nothing to show yet
};

nlohmann::json read_json(const fs::path &p);  // null when missing or unreadable
// j[key] when j is an object that holds it, else an empty object (which iterates as empty).
const nlohmann::json &member(const nlohmann::json &j, const char *key);
std::optional<analysis::Table> read_table(const fs::path &p);
// A JSON value in the display units of its SI unit ("70 mm/s"); text as it is.
std::string shown(const nlohmann::json &v, const std::string &unit);
// The SI unit of an input or metric: from `units` (optimum.json's) when it names it, else spreadmap's own
// names (U, omega, vs, rq, ...), else "".
std::string unit_of(const std::string &name, const nlohmann::json &units = nullptr);
std::string number(double v, const char *format = "{:.3g}");  // "–" for NaN
double field(const nlohmann::json &j, const char *key);         // NaN when absent or not a number
std::string paragraph(const std::string &text);                 // <p> of escaped text
std::string warning(const std::string &text);                   // a highlighted <p>
std::string figure(const fs::path &png, const std::string &caption, const std::string &css_class = "wide");
// "R_q" for rq, "V_s" for vs, the name otherwise.
std::string metric_label(const std::string &name);

}  // namespace spreadmap::report
