#include "workflow/spreading/size_table.hpp"

#include <fmt/format.h>

#include <cmath>
#include <map>
#include <optional>
#include <stdexcept>
#include <vector>
#include <nlohmann/json.hpp>
#include <yaml-cpp/yaml.h>

#include "analysis/table.hpp"
#include "core/suggest.hpp"
#include "core/units.hpp"
#include "workflow/spreading/csv_columns.hpp"

namespace spreadmap {
namespace {

const std::string key_path = "scene.powder.table";
const std::vector<std::string> known_columns = {"diameter", "from", "to", "fraction"};
const char *const row_shapes = "each row is {diameter, fraction} or {from, to, fraction} (a size class)";

struct Cell {
  std::string text;
  Location at;
};

struct Row {
  std::map<std::string, Cell> cells;
  Location at;
};

void unknown_column(const std::string &name, const Location &at, Diagnostics &diag) {
  const std::string near = closest(name, known_columns);
  diag.error(at, key_path, fmt::format("unknown column '{}'", name),
             (near.empty() ? "" : "did you mean '" + near + "'? ") + std::string(row_shapes));
}

std::optional<std::vector<Row>> rows_from_yaml(const YAML::Node &node, const std::string &file, Diagnostics &diag) {
  if (!node.IsSequence() || node.size() == 0) {
    diag.error(Location::of(file, node), key_path, "expected a list of rows or the name of a CSV file",
               std::string(row_shapes) +
                   ", e.g. table: [{diameter: 20 um, fraction: 0.3}, {diameter: 40 um, "
                   "fraction: 0.7}], or table: sizes.csv");
    return std::nullopt;
  }
  std::vector<Row> rows;
  bool ok = true;
  for (const auto &item : node) {
    Row row{{}, Location::of(file, item)};
    if (!item.IsMap()) {
      diag.error(row.at, key_path, "a row must be a mapping", row_shapes);
      ok = false;
      continue;
    }
    for (const auto &kv : item) {
      const std::string name = lower(kv.first.as<std::string>());
      if (std::find(known_columns.begin(), known_columns.end(), name) == known_columns.end()) {
        unknown_column(name, Location::of(file, kv.first), diag);
        ok = false;
      } else if (!kv.second.IsScalar()) {
        diag.error(Location::of(file, kv.second), key_path, fmt::format("{}: expected a number", name));
        ok = false;
      } else {
        row.cells[name] = {kv.second.Scalar(), Location::of(file, kv.second)};
      }
    }
    rows.push_back(std::move(row));
  }
  if (!ok) return std::nullopt;
  return rows;
}

std::optional<std::vector<Row>> rows_from_csv(const std::string &path, Diagnostics &diag) {
  analysis::Table table;
  try {
    table = analysis::Table::read_csv(path);
  } catch (const std::exception &e) {
    diag.error(fmt::format("{}: {}\n  {}; the first line names the columns", e.what(), key_path, row_shapes));
    return std::nullopt;
  }
  bool ok = true;
  std::vector<std::pair<std::string, std::string>> columns;
  for (const auto &header : table.columns()) {
    columns.push_back(column_name_and_unit(header));
    const auto &[name, unit] = columns.back();
    if (std::find(known_columns.begin(), known_columns.end(), name) == known_columns.end()) {
      unknown_column(name, Location{path, 1, 0}, diag);
      ok = false;
    } else if (!unit.empty() && !parse_unit(unit)) {
      diag.error(Location{path, 1, 0}, key_path, fmt::format("column '{}': unknown unit '{}'", name, unit),
                 "write e.g. 'from [um]' or 'fraction [%]'");
      ok = false;
    }
  }
  if (table.rows() == 0) {
    diag.error(Location{path}, key_path, "the table has a header but no rows", row_shapes);
    ok = false;
  }
  if (!ok) return std::nullopt;
  std::vector<Row> rows;
  for (std::size_t r = 0; r < table.rows(); ++r) {
    Row row{{}, Location{path, static_cast<int>(table.line(r)), 0}};
    for (std::size_t c = 0; c < columns.size(); ++c) {
      const auto &[name, unit] = columns[c];
      const std::string &text = table.text(r, c);
      row.cells[name] = {with_column_unit(text, unit), row.at};
    }
    rows.push_back(std::move(row));
  }
  return rows;
}

// The value of a cell in SI, or nullopt with the problem reported.
std::optional<double> value(const Row &row, const char *name, const char *si_unit, Diagnostics &diag) {
  const auto it = row.cells.find(name);
  if (it == row.cells.end()) {
    diag.error(row.at, key_path, fmt::format("the row has no {}", name), row_shapes);
    return std::nullopt;
  }
  try {
    return parse_in(it->second.text, si_unit);
  } catch (const std::invalid_argument &e) {
    diag.error(it->second.at, key_path, fmt::format("{}: {}", name, e.what()));
    return std::nullopt;
  }
}

std::optional<double> size(const Row &row, const char *name, Diagnostics &diag) {
  const auto d = value(row, name, "m", diag);
  if (d && !(*d >= 1e-6 && *d <= 0.1)) {
    diag.error(row.cells.at(name).at, key_path,
               fmt::format("{} = {} is outside [1e-06, 0.1] m", name, row.cells.at(name).text),
               "sizes carry their unit (20 um), or the CSV header gives it (from [um])");
    return std::nullopt;
  }
  return d;
}

std::string with_um(double d) { return fmt::format("{:.4g} um", d * 1e6); }

// The rows in SI, checked: one kind, sizes in order, fractions >= 0 summing to 1.
nlohmann::json checked_rows(const std::vector<Row> &rows, const Location &table_at, const std::string &basis,
                            Diagnostics &diag) {
  const bool classes = !rows.front().cells.count("diameter");
  nlohmann::json out = nlohmann::json::array();
  double sum = 0, previous = 0;
  bool ok = true;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const Row &row = rows[i];
    const bool one_diameter = row.cells.count("diameter"), a_class = row.cells.count("from") || row.cells.count("to");
    if ((one_diameter && a_class) || (classes ? one_diameter : a_class)) {
      diag.error(row.at, key_path, "rows of one diameter and size classes are mixed",
                 "give every row a diameter, or every row from and to");
      ok = false;
      continue;
    }
    const auto fraction = value(row, "fraction", "-", diag);
    if (fraction && !(*fraction >= 0)) {
      diag.error(row.cells.at("fraction").at, key_path,
                 fmt::format("fraction {} is negative", row.cells.at("fraction").text),
                 "a fraction is a share of the powder: 0 or more");
      ok = false;
    }
    const auto lo = size(row, classes ? "from" : "diameter", diag);
    const auto hi = classes ? size(row, "to", diag) : lo;
    if (!fraction || !lo || !hi) {
      ok = false;
      continue;
    }
    if (classes && !(*lo < *hi)) {
      diag.error(row.at, key_path,
                 fmt::format("the class from {} to {} is empty or reversed", with_um(*lo), with_um(*hi)),
                 "from is the finer sieve (what stays on it), to the coarser (what passed it)");
      ok = false;
    } else if (i > 0 && !(*lo >= previous && (classes || *lo > previous))) {
      diag.error(row.at, key_path,
                 classes ? fmt::format("the class from {} overlaps the one before, which ends at {}", with_um(*lo),
                                       with_um(previous))
                         : fmt::format("sizes out of order: {} after {}", with_um(*lo), with_um(previous)),
                 "list the rows from the smallest size to the largest, each size once");
      ok = false;
    }
    previous = *hi;
    sum += *fraction;
    out.push_back(classes ? nlohmann::json{{"from", *lo}, {"to", *hi}, {"fraction", *fraction}}
                          : nlohmann::json{{"diameter", *lo}, {"fraction", *fraction}});
  }
  if (ok && !(std::abs(sum - 1) <= table_sum_tolerance)) {
    const bool percent = std::abs(sum - 100) <= 100 * table_sum_tolerance;
    diag.error(table_at, key_path,
               fmt::format("the fractions sum to {:.6g}, not 1 (tolerance {})", sum, table_sum_tolerance),
               percent ? "they look like percent: divide them by 100, or write each with a % sign (8 %)"
                       : fmt::format("they are shares of the whole powder by {}: add the missing rows or rescale "
                                     "them to sum to 1",
                                     basis));
    ok = false;
  }
  return ok ? out : nlohmann::json();
}

}  // namespace

void resolve_size_table(nlohmann::json &powder, const YAML::Node &node, const std::string &scene_file,
                        const std::filesystem::path &scene_dir, Diagnostics &diag) {
  if (!node || !powder.contains("table") || powder["table"].is_null()) return;
  const std::string basis = powder.value("basis", "number");
  std::optional<std::vector<Row>> rows;
  Location table_at = Location::of(scene_file, node);
  if (node.IsScalar()) {
    const std::filesystem::path csv = std::filesystem::path(node.Scalar()).is_absolute()
                                          ? std::filesystem::path(node.Scalar())
                                          : scene_dir / node.Scalar();
    if (!std::filesystem::is_regular_file(csv)) {
      diag.error(table_at, key_path, fmt::format("no CSV file {}", csv.string()),
                 "a table file's name is relative to the folder of the file that names it");
      powder["table"] = nullptr;
      return;
    }
    rows = rows_from_csv(csv.string(), diag);
    table_at = Location{csv.string()};
  } else {
    rows = rows_from_yaml(node, scene_file, diag);
  }
  powder["table"] = rows ? checked_rows(*rows, table_at, basis, diag) : nlohmann::json();
}

}  // namespace spreadmap
