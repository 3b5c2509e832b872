// Test helper: small parts written as STL files (ASCII and binary) from the same single-precision
// corners, so that both formats hold the same numbers, in a folder of their own.
#pragma once
#include <spreadmap/mesh/stl.hpp>

#include <array>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <unistd.h>

namespace spreadmap::mesh::testing {

// A fresh folder for one test's files, removed with everything in it.
struct Folder {
  std::filesystem::path dir;
  explicit Folder(const std::string &name)
      : dir(std::filesystem::temp_directory_path() / (name + "_" + std::to_string(::getpid()))) {
    std::filesystem::create_directories(dir);
  }
  ~Folder() { std::filesystem::remove_all(dir); }
  std::string file(const std::string &name) const { return (dir / name).string(); }
};

using Facet = std::array<float, 9>;  // three corners, counter-clockwise seen from outside

inline void write_ascii(const std::string &file, const std::vector<Facet> &facets) {
  std::FILE *f = std::fopen(file.c_str(), "w");
  std::fprintf(f, "solid part\n");
  for (const Facet &t : facets) {
    std::fprintf(f, "  facet normal 0 0 0\n    outer loop\n");
    for (int v = 0; v < 3; ++v) std::fprintf(f, "      vertex %.9g %.9g %.9g\n", t[3 * v], t[3 * v + 1], t[3 * v + 2]);
    std::fprintf(f, "    endloop\n  endfacet\n");
  }
  std::fprintf(f, "endsolid part\n");
  std::fclose(f);
}

inline void write_binary(const std::string &file, const std::vector<Facet> &facets) {
  std::ofstream out(file, std::ios::binary);
  const std::string header(80, ' ');
  out.write(header.data(), 80);
  const auto count = static_cast<std::uint32_t>(facets.size());
  out.write(reinterpret_cast<const char *>(&count), 4);
  for (const Facet &t : facets) {
    const float normal[3] = {0, 0, 0};
    const std::uint16_t attributes = 0;
    out.write(reinterpret_cast<const char *>(normal), sizeof normal);
    out.write(reinterpret_cast<const char *>(t.data()), sizeof(float) * 9);
    out.write(reinterpret_cast<const char *>(&attributes), 2);
  }
}

// The plate [0, n a] x [0, n a] at height z, n x n squares of two triangles each, facing +z; the
// diagonals alternate, so a corner is shared by up to six triangles.
inline std::vector<Facet> plate(int n, float a, float z = 0) {
  std::vector<Facet> out;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const float x0 = i * a, x1 = (i + 1) * a, y0 = j * a, y1 = (j + 1) * a;
      if ((i + j) % 2 == 0) {
        out.push_back({x0, y0, z, x1, y0, z, x1, y1, z});
        out.push_back({x0, y0, z, x1, y1, z, x0, y1, z});
      } else {
        out.push_back({x0, y0, z, x1, y0, z, x0, y1, z});
        out.push_back({x1, y0, z, x1, y1, z, x0, y1, z});
      }
    }
  return out;
}

// The box [lo, hi], twelve triangles facing outwards.
inline std::vector<Facet> box(const std::array<float, 3> &lo, const std::array<float, 3> &hi) {
  auto p = [&](int c) -> std::array<float, 3> {
    return {c & 1 ? hi[0] : lo[0], c & 2 ? hi[1] : lo[1], c & 4 ? hi[2] : lo[2]};
  };
  // each face's corners counter-clockwise seen from outside
  const int faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  std::vector<Facet> out;
  for (const auto &f : faces)
    for (const auto &tri : {std::array<int, 3>{f[0], f[1], f[2]}, std::array<int, 3>{f[0], f[2], f[3]}}) {
      Facet t{};
      for (int v = 0; v < 3; ++v)
        for (int d = 0; d < 3; ++d) t[3 * v + d] = p(tri[v])[d];
      out.push_back(t);
    }
  return out;
}

// A square pyramid: base [-b, b]^2 at z = 0, apex at (0, 0, h); closed.
inline std::vector<Facet> pyramid(float b, float h) {
  const std::array<float, 3> apex{0, 0, h}, c[4] = {{-b, -b, 0}, {b, -b, 0}, {b, b, 0}, {-b, b, 0}};
  std::vector<Facet> out;
  for (int k = 0; k < 4; ++k) {
    const auto &a = c[k], &n = c[(k + 1) % 4];
    out.push_back({a[0], a[1], a[2], n[0], n[1], n[2], apex[0], apex[1], apex[2]});
  }
  out.push_back({c[0][0], c[0][1], 0, c[2][0], c[2][1], 0, c[1][0], c[1][1], 0});
  out.push_back({c[0][0], c[0][1], 0, c[3][0], c[3][1], 0, c[2][0], c[2][1], 0});
  return out;
}

}  // namespace spreadmap::mesh::testing
