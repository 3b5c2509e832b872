// Reading an STL file (ASCII or binary) into triangles in metres. Host only.
//
// STL carries no unit, so the caller gives the metres per file unit (`unit: mm` -> 1e-3). Both
// formats hold single-precision coordinates (the format says so for ASCII too): ASCII numbers are
// read as float, so the ASCII and binary files of one part give the same triangles, bit for bit.
// The facet normals in the file are ignored: a triangle faces where its corners turn counter-clockwise
// (right-hand rule), as the format defines. Every fault is a ParamError that names the file, the line
// (ASCII) or facet (binary), and the fix.
#pragma once
#include <spreadmap/params.hpp>

#include <array>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

namespace spreadmap::mesh {

using Point = std::array<double, 3>;
struct Triangle {
  Point corner[3];  // [m], counter-clockwise seen from the side the face points to
};

// Metres per unit for the names `unit:` accepts ("m|cm|mm|um|in"); 0 for any other name.
inline double metres_per(const std::string &unit) {
  if (unit == "m") return 1.0;
  if (unit == "cm") return 1e-2;
  if (unit == "mm") return 1e-3;
  if (unit == "um") return 1e-6;
  if (unit == "in") return 0.0254;
  return 0.0;
}

namespace detail {

inline ParamError stl_error(const std::string &file, const std::string &where, const std::string &what,
                            const std::string &fix) {
  return ParamError(file + (where.empty() ? "" : ":" + where) + ": " + what + "; " + fix);
}

// The three corners of one facet, checked: finite, and spanning an area (not a sliver of zero width).
inline Triangle checked_triangle(const float (&c)[9], double scale, const std::string &file,
                                 const std::string &where) {
  Triangle t;
  for (int k = 0; k < 9; ++k) {
    if (!std::isfinite(c[k]))
      throw stl_error(file, where, "a corner has a coordinate that is not a finite number",
                      "repair the mesh or export it again from the CAD model");
    t.corner[k / 3][k % 3] = static_cast<double>(c[k]) * scale;
  }
  double e[3][3], longest = 0;
  for (int k = 0; k < 3; ++k) {
    for (int d = 0; d < 3; ++d) e[k][d] = t.corner[(k + 1) % 3][d] - t.corner[k][d];
    longest = std::fmax(longest, e[k][0] * e[k][0] + e[k][1] * e[k][1] + e[k][2] * e[k][2]);
  }
  const double ax = e[0][1] * e[1][2] - e[0][2] * e[1][1], ay = e[0][2] * e[1][0] - e[0][0] * e[1][2],
               az = e[0][0] * e[1][1] - e[0][1] * e[1][0];
  if (!(std::sqrt(ax * ax + ay * ay + az * az) > 1e-12 * longest))
    throw stl_error(file, where, "a degenerate triangle (two corners coincide or all three lie on one line)",
                    "remove it: repair the mesh or export it again from the CAD model");
  return t;
}

inline std::vector<Triangle> read_binary(const std::string &bytes, double scale, const std::string &file) {
  std::uint32_t count = 0;
  std::memcpy(&count, bytes.data() + 80, 4);
  std::vector<Triangle> out;
  out.reserve(count);
  for (std::uint32_t f = 0; f < count; ++f) {
    float c[9];
    std::memcpy(c, bytes.data() + 84 + 50 * std::size_t(f) + 12, sizeof c);  // skip the facet's normal
    out.push_back(checked_triangle(c, scale, file, "facet " + std::to_string(f + 1)));
  }
  return out;
}

// One whitespace-separated word at a time, with the line it is on.
class Words {
 public:
  explicit Words(const std::string &text) : text_(text) {}
  bool next(std::string &word) {
    while (pos_ < text_.size() && std::isspace(static_cast<unsigned char>(text_[pos_]))) {
      if (text_[pos_] == '\n') ++line_;
      ++pos_;
    }
    if (pos_ >= text_.size()) return false;
    const std::size_t from = pos_;
    while (pos_ < text_.size() && !std::isspace(static_cast<unsigned char>(text_[pos_]))) ++pos_;
    word.assign(text_, from, pos_ - from);
    return true;
  }
  std::string where() const { return "line " + std::to_string(line_); }
  void skip_line() {
    while (pos_ < text_.size() && text_[pos_] != '\n') ++pos_;
  }

 private:
  const std::string &text_;
  std::size_t pos_ = 0;
  std::size_t line_ = 1;
};

inline std::string lower(std::string s) {
  for (char &c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

inline void expect_word(Words &w, const std::string &want, const std::string &file) {
  std::string word;
  if (!w.next(word))
    throw stl_error(file, w.where(), "the file ends inside a facet (expected '" + want + "')",
                    "the file is truncated: export it again");
  if (lower(word) != want)
    throw stl_error(file, w.where(), "expected '" + want + "', found '" + word + "'",
                    "an ASCII STL facet is: facet normal nx ny nz / outer loop / 3 x vertex x y z / endloop / "
                    "endfacet");
}

inline float read_number(Words &w, const std::string &file) {
  std::string word;
  if (!w.next(word))
    throw stl_error(file, w.where(), "the file ends inside a facet (expected a number)",
                    "the file is truncated: export it again");
  char *end = nullptr;
  const float v = std::strtof(word.c_str(), &end);
  if (end == word.c_str() || *end != '\0')
    throw stl_error(file, w.where(), "'" + word + "' is not a number", "repair the file or export it again");
  return v;
}

inline std::vector<Triangle> read_ascii(const std::string &text, double scale, const std::string &file) {
  Words w(text);
  std::string word;
  w.next(word);  // "solid"
  w.skip_line();  // its name
  std::vector<Triangle> out;
  while (w.next(word)) {
    const std::string key = lower(word);
    if (key == "endsolid") return out;
    if (key != "facet")
      throw stl_error(file, w.where(), "expected 'facet' or 'endsolid', found '" + word + "'",
                      "repair the file or export it again");
    const std::string at = w.where();
    expect_word(w, "normal", file);
    for (int k = 0; k < 3; ++k) read_number(w, file);
    expect_word(w, "outer", file);
    expect_word(w, "loop", file);
    float c[9];
    for (int v = 0; v < 3; ++v) {
      expect_word(w, "vertex", file);
      for (int d = 0; d < 3; ++d) c[3 * v + d] = read_number(w, file);
    }
    expect_word(w, "endloop", file);
    expect_word(w, "endfacet", file);
    out.push_back(checked_triangle(c, scale, file, at));
  }
  throw stl_error(file, w.where(), "the file ends without 'endsolid'", "the file is truncated: export it again");
}

}  // namespace detail

// A file's bytes, or a refusal naming it (missing or unreadable).
inline std::string read_file_bytes(const std::string &file) {
  std::ifstream in(file, std::ios::binary);
  if (!in)
    throw detail::stl_error(file, "", "cannot be opened (missing or unreadable)",
                            "check the path: it is relative to the file that names it");
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// The triangles of an STL file's bytes, in metres (`scale`: metres per file unit); the caller read
// them (read_file_bytes), e.g. to take their digest too.
inline std::vector<Triangle> read_stl_bytes(const std::string &bytes, double scale, const std::string &file) {
  if (bytes.empty()) throw detail::stl_error(file, "", "the file is empty", "export the part again");
  std::uint32_t count = 0;
  if (bytes.size() >= 84) std::memcpy(&count, bytes.data() + 80, 4);
  const bool binary_size = bytes.size() >= 84 && bytes.size() == 84 + 50 * std::uint64_t(count);
  std::size_t first = bytes.find_first_not_of(" \t\r\n");
  const bool ascii = first != std::string::npos && detail::lower(bytes.substr(first, 5)) == "solid" &&
                     bytes.find('\0') == std::string::npos;
  std::vector<Triangle> out;
  if (binary_size) out = detail::read_binary(bytes, scale, file);
  else if (ascii) out = detail::read_ascii(bytes, scale, file);
  else if (bytes.size() >= 84)
    throw detail::stl_error(file, "",
                            "a damaged binary STL: its header counts " + std::to_string(count) + " facets (" +
                                std::to_string(84 + 50 * std::uint64_t(count)) + " bytes) but the file has " +
                                std::to_string(bytes.size()) + " bytes",
                            "the file is truncated or not an STL: export it again");
  else
    throw detail::stl_error(file, "", "not an STL file (too short for binary, and no 'solid' to start ASCII)",
                            "export the part as STL");
  if (out.empty()) throw detail::stl_error(file, "", "the file holds no triangles", "export the part again");
  return out;
}

// The triangles of an STL file, in metres.
inline std::vector<Triangle> read_stl(const std::string &file, double scale) {
  return read_stl_bytes(read_file_bytes(file), scale, file);
}

}  // namespace spreadmap::mesh
