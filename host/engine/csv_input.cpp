#include <engine/csv_input.hpp>
#include <engine/errors.hpp>

#include <core/csv_line.hpp>

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <fmt/format.h>
#include <fstream>
#include <numbers>
#include <optional>
#include <string_view>

namespace spreadmap::engine {

namespace {

constexpr std::array<std::string_view, 14> known = {"x",  "y",  "z",  "radius", "vx",      "vy",    "vz",
                                                    "wx", "wy", "wz", "mass",   "density", "fixed", "id"};
constexpr int density_column = 11, fixed_column = 12, id_column = 13;
constexpr std::size_t n_required = 4;

std::string_view trim(std::string_view s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
  return s;
}

std::string lower(std::string_view s) {
  std::string out(s);
  for (auto &c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

}  // namespace

ParticleSet read_particles_csv(const std::filesystem::path &path, std::vector<std::size_t> *lines) {
  std::ifstream in(path);
  if (!in) throw SetupError(fmt::format("{}: cannot open the particle file for reading", path.string()));
  const std::string file = path.string();
  std::string line;
  std::size_t line_no = 0;
  std::vector<int> slot;  // per CSV column: index into `known`
  bool have_header = false;
  ParticleSet s;
  std::vector<double> density;
  std::array<std::vector<double> *, 12> columns = {&s.x,  &s.y,  &s.z,  &s.radius, &s.vx,   &s.vy,
                                                   &s.vz, &s.wx, &s.wy, &s.wz,     &s.mass, &density};
  std::array<bool, known.size()> present{};
  while (std::getline(in, line)) {
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const std::string_view body = trim(line);
    if (body.empty() || body.front() == '#') continue;
    std::vector<core::CsvCell> fields;
    try {
      fields = core::split_csv_line(line, fmt::format("{}:{}", file, line_no));
    } catch (const std::runtime_error &e) {
      throw SetupError(e.what());
    }
    if (!have_header) {
      for (const auto &f : fields) {
        const std::string name = lower(f.text);
        const auto it = std::find(known.begin(), known.end(), name);
        if (it == known.end())
          throw SetupError(
              fmt::format("{}:{}:{}: unknown column '{}'; allowed: x, y, z, radius (required), vx, vy, vz, "
                          "wx, wy, wz, mass or density, fixed, id",
                          file, line_no, f.column, f.text));
        const int k = static_cast<int>(it - known.begin());
        if (present[k])
          throw SetupError(fmt::format("{}:{}:{}: column '{}' appears twice", file, line_no, f.column, f.text));
        present[k] = true;
        slot.push_back(k);
      }
      for (std::size_t k = 0; k < n_required; ++k)
        if (!present[k])
          throw SetupError(fmt::format("{}:{}:1: the header has no '{}' column; required: x, y, z, radius", file,
                                       line_no, known[k]));
      if (present[10] && present[density_column])
        throw SetupError(
            fmt::format("{}:{}:1: the header names both mass and density; keep one of them", file, line_no));
      have_header = true;
      continue;
    }
    if (fields.size() != slot.size())
      throw SetupError(fmt::format("{}:{}:{}: {} values on this line, the header names {} columns", file, line_no,
                                   fields.size() > slot.size() ? fields[slot.size()].column : line.size() + 1,
                                   fields.size(), slot.size()));
    for (std::size_t c = 0; c < fields.size(); ++c) {
      const auto &f = fields[c];
      double v = 0;
      const auto res = std::from_chars(f.text.data(), f.text.data() + f.text.size(), v);
      if (res.ec != std::errc{} || res.ptr != f.text.data() + f.text.size() || !std::isfinite(v))
        throw SetupError(fmt::format("{}:{}:{}: column '{}' holds '{}', not a finite number", file, line_no, f.column,
                                     known[slot[c]], f.text));
      const int k = slot[c];
      if (k == 3 && !(v > 0))
        throw SetupError(fmt::format("{}:{}:{}: radius = {} m; a radius must be > 0", file, line_no, f.column, v));
      if (k == 10 && !(v > 0))
        throw SetupError(fmt::format("{}:{}:{}: mass = {} kg; a mass must be > 0", file, line_no, f.column, v));
      if (k == density_column && !(v > 0))
        throw SetupError(
            fmt::format("{}:{}:{}: density = {} kg/m^3; a density must be > 0", file, line_no, f.column, v));
      if (k == fixed_column) {
        if (v != 0 && v != 1)
          throw SetupError(fmt::format("{}:{}:{}: fixed = {}; write 1 (the particle never moves) or 0", file, line_no,
                                       f.column, f.text));
        s.fixed.push_back(static_cast<std::uint8_t>(v));
      } else if (k == id_column) {
        if (v < 0 || v >= 4294967295.0 || v != std::floor(v))
          throw SetupError(fmt::format("{}:{}:{}: id = {}; an id must be a whole number in [0, 4294967294]", file,
                                       line_no, f.column, f.text));
        s.id.push_back(static_cast<std::uint32_t>(v));
      } else {
        columns[k]->push_back(v);
      }
    }
    if (lines) lines->push_back(line_no);
  }
  if (!have_header)
    throw SetupError(fmt::format("{}:1:1: empty file; expected a header line such as 'x,y,z,radius'", file));
  for (std::size_t i = 0; i < density.size(); ++i)
    s.mass.push_back(density[i] * 4.0 / 3.0 * std::numbers::pi * s.radius[i] * s.radius[i] * s.radius[i]);
  return s;
}

}  // namespace spreadmap::engine
