#include "workflow/spreading/height_map_file.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>
#include <vector>

#include "analysis/table.hpp"
#include "core/suggest.hpp"
#include "core/units.hpp"
#include "workflow/spreading/csv_columns.hpp"

namespace spreadmap {
namespace {

const std::vector<std::string> columns_wanted = {"x", "y", "height"};
const char *const file_shape = "the first line names the columns x, y and height, e.g. 'x [um],y [um],height [um]'";
constexpr double max_height = 0.1;  // m: beyond it the unit is surely wrong
constexpr std::size_t errors_shown = 5;

// The text with comment lines (# first) blanked, so that the table's line numbers stay the file's.
std::string without_comments(std::string text) {
  std::size_t pos = 0;
  while (pos < text.size()) {
    const std::size_t nl = std::min(text.find('\n', pos), text.size());
    const std::size_t first = text.find_first_not_of(" \t", pos);
    if (first < nl && text[first] == '#') std::fill(text.begin() + long(pos), text.begin() + long(nl), ' ');
    pos = nl + 1;
  }
  return text;
}

struct Point {
  double x, y, h;
  int line;
};

// One axis of the grid: its first coordinate, spacing and count, from the points' coordinates.
struct GridAxis {
  double first = 0, spacing = 0;
  std::size_t n = 0;
  // The grid index of `v`, or nullopt when v is off the grid by more than grid_tolerance.
  std::optional<std::size_t> index(double v) const {
    const double u = (v - first) / spacing, k = std::round(u);
    if (std::abs(u - k) > grid_tolerance || k < 0 || k >= double(n)) return std::nullopt;
    return static_cast<std::size_t>(k);
  }
};

// The distinct values (within a millionth of the range) give the count; first and last the spacing.
GridAxis axis_of(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const double merge = (v.back() - v.front()) * 1e-6;
  std::size_t distinct = 1;
  for (std::size_t i = 1; i < v.size(); ++i)
    if (v[i] - v[i - 1] > merge) ++distinct;
  GridAxis a;
  a.first = v.front();
  a.n = distinct;
  a.spacing = distinct > 1 ? (v.back() - v.front()) / double(distinct - 1) : 0;
  return a;
}

std::string mm(double v) { return fmt::format("{:.6g} mm", v * 1e3); }

// The column of each wanted name: its index and its unit as the header gives it.
using HeightColumns = std::map<std::string, std::pair<std::size_t, std::string>>;

// Refusals of rows or points, the first errors_shown of them reported in full.
struct Refusals {
  Diagnostics &diag;
  const std::string &key;
  std::size_t count = 0;

  void operator()(const Location &at, const std::string &what, const std::string &fix) {
    if (++count <= errors_shown) diag.error(at, key, what, fix);
  }
  // False (with a count of those not shown) when any were refused.
  bool none(const std::string &path, const char *what) const {
    if (count == 0) return true;
    if (count > errors_shown)
      diag.error(fmt::format("{}: {} more {} refused", path, count - errors_shown, what));
    return false;
  }
};

// The columns x, y, height, each once, with a unit the parser knows, and a count of rows a grid can
// have; nullopt (reported) otherwise.
std::optional<HeightColumns> height_columns(const analysis::Table &table, const std::string &path,
                                            const std::string &key, Diagnostics &diag) {
  HeightColumns column;
  bool ok = true;
  for (std::size_t c = 0; c < table.cols(); ++c) {
    const auto [name, unit] = column_name_and_unit(table.columns()[c]);
    if (std::find(columns_wanted.begin(), columns_wanted.end(), name) == columns_wanted.end()) {
      const std::string near = closest(name, columns_wanted);
      diag.error(Location{path, 1, 0}, key, fmt::format("unknown column '{}'", name),
                 (near.empty() ? "" : "did you mean '" + near + "'? ") + std::string(file_shape));
      ok = false;
    } else if (!unit.empty() && !parse_unit(unit)) {
      diag.error(Location{path, 1, 0}, key, fmt::format("column '{}': unknown unit '{}'", name, unit),
                 "write e.g. 'height [um]'");
      ok = false;
    } else {
      column[name] = {c, unit};
    }
  }
  for (const auto &name : columns_wanted)
    if (ok && !column.count(name)) {
      diag.error(Location{path, 1, 0}, key, fmt::format("no column '{}'", name), file_shape);
      ok = false;
    }
  if (ok && table.rows() < 4) {
    diag.error(Location{path}, key, fmt::format("{} points; a grid needs at least 2 x 2", table.rows()), file_shape);
    ok = false;
  }
  if (ok && double(table.rows()) > height_map_max_points) {
    diag.error(Location{path}, key, fmt::format("{} points, more than {:g}", table.rows(), height_map_max_points),
               "resample the map to a coarser grid: the substrate's spheres sample it at their own spacing");
    ok = false;
  }
  if (!ok) return std::nullopt;
  return column;
}

// Each row's point in metres; a row without lengths, or with a height beyond max_height, is refused.
std::vector<Point> height_points(const analysis::Table &table, const HeightColumns &column, const std::string &path,
                                 Refusals &refuse) {
  std::vector<Point> points;
  for (std::size_t r = 0; r < table.rows(); ++r) {
    const Location at{path, static_cast<int>(table.line(r)), 0};
    double v[3];
    bool row_ok = true;
    for (std::size_t k = 0; k < 3 && row_ok; ++k) {
      const auto &[c, unit] = column.at(columns_wanted[k]);
      try {
        v[k] = parse_in(with_column_unit(table.text(r, c), unit), "m");
      } catch (const std::invalid_argument &e) {
        refuse(at, fmt::format("{}: {}", columns_wanted[k], e.what()),
               "a length with its unit (12.5 um), or a bare number under a header with one (height [um])");
        row_ok = false;
      }
    }
    if (!row_ok) continue;
    if (std::abs(v[2]) > max_height) {
      refuse(at, fmt::format("height {} is beyond {:g} mm", mm(v[2]), max_height * 1e3),
             "is the unit right? bare numbers are metres unless the header gives a unit: 'height [um]'");
      continue;
    }
    points.push_back({v[0], v[1], v[2], at.line});
  }
  return points;
}

// The points placed on the grid of the axes; a point off the grid or given twice, or a grid point
// missing, is refused.
powder::HeightField grid_of_points(const std::vector<Point> &points, const GridAxis &ax, const GridAxis &ay,
                                  const std::string &path, Refusals &refuse) {
  powder::HeightField map{ax.n, ay.n, ax.spacing, ay.spacing, std::vector<double>(ax.n * ay.n)};
  std::vector<int> line_of(map.h.size(), 0);
  for (const auto &p : points) {
    const auto ix = ax.index(p.x), iy = ay.index(p.y);
    if (!ix || !iy) {
      refuse(Location{path, p.line, 0},
             fmt::format("the point ({}, {}) is off the grid of {} x {} points spaced {} along x and {} along y",
                         mm(p.x), mm(p.y), ax.n, ay.n, mm(ax.spacing), mm(ay.spacing)),
             "give heights on a regular grid (equal spacings along x and along y)");
      continue;
    }
    const std::size_t at = *iy * ax.n + *ix;
    if (line_of[at] != 0) {
      refuse(Location{path, p.line, 0},
             fmt::format("the point ({}, {}) is given twice, here and on line {}", mm(p.x), mm(p.y), line_of[at]),
             "give each grid point once");
      continue;
    }
    line_of[at] = p.line;
    map.h[at] = p.h;
  }
  if (refuse.count == 0 && points.size() < map.h.size()) {
    const auto hole = std::find(line_of.begin(), line_of.end(), 0) - line_of.begin();
    const std::size_t ix = std::size_t(hole) % ax.n, iy = std::size_t(hole) / ax.n;
    refuse(
        Location{path},
        fmt::format("{} of the grid's {} x {} points are missing, the first at ({}, {})", map.h.size() - points.size(),
                    ax.n, ay.n, mm(ax.first + double(ix) * ax.spacing), mm(ay.first + double(iy) * ay.spacing)),
        "give a height at every grid point");
  }
  return map;
}

}  // namespace

std::optional<powder::HeightField> parse_height_map(const std::string &text, const std::filesystem::path &csv,
                                                   const std::string &key, Diagnostics &diag) {
  const std::string path = csv.string();
  analysis::Table table;
  try {
    table = analysis::Table::parse_csv(without_comments(text), path);
  } catch (const std::exception &e) {
    diag.error(fmt::format("{}: {}\n  {}", e.what(), key, file_shape));
    return std::nullopt;
  }
  const std::optional<HeightColumns> column = height_columns(table, path, key, diag);
  if (!column) return std::nullopt;

  Refusals refuse{diag, key};
  const std::vector<Point> points = height_points(table, *column, path, refuse);
  if (!refuse.none(path, "rows")) return std::nullopt;

  std::vector<double> xs, ys;
  for (const auto &p : points) xs.push_back(p.x), ys.push_back(p.y);
  const GridAxis ax = axis_of(xs), ay = axis_of(ys);
  if (ax.n < 2 || ay.n < 2) {
    diag.error(Location{path}, key,
               fmt::format("the points span {} x {} distinct positions; a grid needs at least 2 x 2", ax.n, ay.n),
               file_shape);
    return std::nullopt;
  }
  powder::HeightField map = grid_of_points(points, ax, ay, path, refuse);
  if (!refuse.none(path, "points")) return std::nullopt;
  return map;
}

}  // namespace spreadmap
