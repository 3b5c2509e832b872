#include <core/files.hpp>
#include <engine/errors.hpp>
#include <engine/vtp_io.hpp>

#include <charconv>
#include <fmt/format.h>
#include <fstream>
#include <sstream>

namespace spreadmap::engine {

namespace {

// Shortest text that reads back to the same double.
void put(std::string &out, double v) {
  char buf[32];
  auto res = std::to_chars(buf, buf + sizeof buf, v);
  out.append(buf, res.ptr);
}

void vector_array(std::string &out, const char *name, const std::vector<double> &a, const std::vector<double> &b,
                  const std::vector<double> &c, std::size_t n) {
  out +=
      fmt::format("        <DataArray type=\"Float64\" Name=\"{}\" NumberOfComponents=\"3\" format=\"ascii\">\n", name);
  for (std::size_t i = 0; i < n; ++i) {
    out += "          ";
    put(out, a.empty() ? 0.0 : a[i]);
    out += ' ';
    put(out, b.empty() ? 0.0 : b[i]);
    out += ' ';
    put(out, c.empty() ? 0.0 : c[i]);
    out += '\n';
  }
  out += "        </DataArray>\n";
}

void scalar_array(std::string &out, const char *name, const std::vector<double> &a, std::size_t n) {
  out += fmt::format("        <DataArray type=\"Float64\" Name=\"{}\" format=\"ascii\">\n", name);
  for (std::size_t i = 0; i < n; ++i) {
    out += i % 6 == 0 ? "          " : " ";
    put(out, a.empty() ? 0.0 : a[i]);
    if (i % 6 == 5 || i + 1 == n) out += '\n';
  }
  out += "        </DataArray>\n";
}

// Integers, ten a line: `value(i)` of point i.
template <class Value>
void integer_array(std::string &out, const char *type, const char *name, std::size_t n, Value &&value) {
  out += fmt::format("        <DataArray type=\"{}\" Name=\"{}\" format=\"ascii\">\n", type, name);
  for (std::size_t i = 0; i < n; ++i) {
    out += i % 10 == 0 ? "          " : " ";
    out += std::to_string(value(i));
    if (i % 10 == 9 || i + 1 == n) out += '\n';
  }
  out += "        </DataArray>\n";
}

}  // namespace

void write_vtp(const std::filesystem::path &path, const ParticleSet &s, double time) {
  s.validate(path.string());
  const std::size_t n = s.size();
  std::string out;
  out.reserve(200 * n + 2000);
  out += "<?xml version=\"1.0\"?>\n";
  out += "<VTKFile type=\"PolyData\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n";
  out += "  <PolyData>\n";
  out += "    <FieldData>\n";
  out += "      <DataArray type=\"Float64\" Name=\"TIME\" NumberOfTuples=\"1\" format=\"ascii\">";
  put(out, time);
  out += "</DataArray>\n    </FieldData>\n";
  out += fmt::format(
      "    <Piece NumberOfPoints=\"{}\" NumberOfVerts=\"{}\" NumberOfLines=\"0\" NumberOfStrips=\"0\" "
      "NumberOfPolys=\"0\">\n",
      n, n);
  out += "      <Points>\n";
  vector_array(out, "Points", s.x, s.y, s.z, n);
  out += "      </Points>\n";
  out += "      <PointData Scalars=\"radius\" Vectors=\"velocity\">\n";
  vector_array(out, "velocity", s.vx, s.vy, s.vz, n);
  vector_array(out, "omega", s.wx, s.wy, s.wz, n);
  scalar_array(out, "radius", s.radius, n);
  if (!s.mass.empty()) scalar_array(out, "mass", s.mass, n);
  integer_array(out, "Int64", "id", n, [&](std::size_t i) { return s.id.empty() ? i : std::size_t(s.id[i]); });
  // only where some particle is fixed: other files stay as they were
  if (!s.fixed.empty()) integer_array(out, "UInt8", "fixed", n, [&](std::size_t i) { return int(s.fixed[i]); });
  out += "      </PointData>\n";
  // One vertex cell per point, so that ParaView draws the particles without a glyph filter.
  out += "      <Verts>\n        <DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n";
  for (std::size_t i = 0; i < n; ++i) {
    out += i % 10 == 0 ? "          " : " ";
    out += std::to_string(i);
    if (i % 10 == 9 || i + 1 == n) out += '\n';
  }
  out += "        </DataArray>\n        <DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n";
  for (std::size_t i = 0; i < n; ++i) {
    out += i % 10 == 0 ? "          " : " ";
    out += std::to_string(i + 1);
    if (i % 10 == 9 || i + 1 == n) out += '\n';
  }
  out += "        </DataArray>\n      </Verts>\n";
  out += "    </Piece>\n  </PolyData>\n</VTKFile>\n";
  write_atomic(path, out);
}

namespace {

struct VtpText {
  std::string text;
  std::string name;

  [[noreturn]] void fail(const std::string &what) const {
    throw SetupError(fmt::format("{}: {}; expected a .vtp particle file written by spreadmap", name, what));
  }
  std::string attribute(std::size_t tag_begin, const std::string &key) const {
    const std::size_t tag_end = text.find('>', tag_begin);
    const std::string needle = " " + key + "=\"";
    const std::size_t k = text.find(needle, tag_begin);
    if (k == std::string::npos || k > tag_end) return {};
    const std::size_t v = k + needle.size();
    return text.substr(v, text.find('"', v) - v);
  }
  // Values of the DataArray named `array`, expecting `count` numbers.
  std::vector<double> numbers(const std::string &array, std::size_t count) const {
    const std::size_t tag = text.find("Name=\"" + array + "\"");
    if (tag == std::string::npos) fail("no DataArray named '" + array + "'");
    const std::size_t begin = text.find('>', tag) + 1, end = text.find("</DataArray>", begin);
    if (end == std::string::npos) fail("DataArray '" + array + "' is not closed");
    const std::size_t tag_begin = text.rfind('<', tag);
    if (attribute(tag_begin, "format") != "ascii") fail("DataArray '" + array + "' is not in ascii format");
    std::vector<double> out;
    out.reserve(count);
    const char *p = text.data() + begin, *e = text.data() + end;
    while (p < e) {
      while (p < e && (*p == ' ' || *p == '\n' || *p == '\r' || *p == '\t')) ++p;
      if (p >= e) break;
      double v;
      auto res = std::from_chars(p, e, v);
      if (res.ec != std::errc{})
        fail(fmt::format("DataArray '{}' holds a value that is not a number near '{}'", array,
                         std::string(p, std::min<std::size_t>(16, e - p))));
      out.push_back(v);
      p = res.ptr;
    }
    if (out.size() != count) fail(fmt::format("DataArray '{}' has {} values, expected {}", array, out.size(), count));
    return out;
  }
};

}  // namespace

VtpContent read_vtp(const std::filesystem::path &path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw SetupError(fmt::format("{}: cannot open the file for reading", path.string()));
  std::ostringstream all;
  all << in.rdbuf();
  VtpText t{all.str(), path.string()};
  if (t.text.find("<VTKFile type=\"PolyData\"") == std::string::npos) t.fail("not a VTK PolyData file");
  const std::size_t piece = t.text.find("<Piece");
  if (piece == std::string::npos) t.fail("no <Piece>");
  const std::string count_text = t.attribute(piece, "NumberOfPoints");
  std::size_t n = 0;
  if (count_text.empty() ||
      std::from_chars(count_text.data(), count_text.data() + count_text.size(), n).ec != std::errc{})
    t.fail("no valid NumberOfPoints");
  VtpContent c;
  const auto time = t.numbers("TIME", 1);
  c.time = time[0];
  auto split = [n](const std::vector<double> &v, std::vector<double> &a, std::vector<double> &b,
                   std::vector<double> &cc) {
    a.resize(n);
    b.resize(n);
    cc.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      a[i] = v[3 * i];
      b[i] = v[3 * i + 1];
      cc[i] = v[3 * i + 2];
    }
  };
  ParticleSet &s = c.particles;
  split(t.numbers("Points", 3 * n), s.x, s.y, s.z);
  split(t.numbers("velocity", 3 * n), s.vx, s.vy, s.vz);
  split(t.numbers("omega", 3 * n), s.wx, s.wy, s.wz);
  s.radius = t.numbers("radius", n);
  if (t.text.find("Name=\"mass\"") != std::string::npos) s.mass = t.numbers("mass", n);
  const auto ids = t.numbers("id", n);
  s.id.resize(n);
  for (std::size_t i = 0; i < n; ++i) s.id[i] = static_cast<std::uint32_t>(ids[i]);
  if (t.text.find("Name=\"fixed\"") != std::string::npos) {
    for (double v : t.numbers("fixed", n)) {
      if (v != 0 && v != 1) t.fail("DataArray 'fixed' holds a value other than 0 and 1");
      s.fixed.push_back(static_cast<std::uint8_t>(v));
    }
  }
  s.validate(path.string());
  return c;
}

void write_pvd(const std::filesystem::path &path, const std::vector<SeriesEntry> &series) {
  std::string out =
      "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"1.0\" byte_order=\"LittleEndian\">\n"
      "  <Collection>\n";
  for (const auto &e : series) {
    out += "    <DataSet timestep=\"";
    put(out, e.time);
    out += fmt::format("\" group=\"\" part=\"0\" file=\"{}\"/>\n", e.file);
  }
  out += "  </Collection>\n</VTKFile>\n";
  write_atomic(path, out);
}

}  // namespace spreadmap::engine
