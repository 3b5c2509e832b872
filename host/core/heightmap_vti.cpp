#include "core/heightmap_vti.hpp"

#include <cstdio>
#include <stdexcept>
#include <string>

#include "core/files.hpp"

namespace sm = spreadmap;

namespace {

// %.17g: every double survives the round trip through the text.
std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

}  // namespace

void sm::write_heightmap_vti(const std::filesystem::path &path, std::uint32_t nx, std::uint32_t ny, double x0,
                             double y0, double cell, const double *h) {
  if (nx == 0 || ny == 0 || !h) throw std::invalid_argument("height map to write is empty: " + path.string());
  if (!(cell > 0)) throw std::invalid_argument("height map cell must be positive, got " + number(cell) + " m");
  const std::string extent = "0 " + std::to_string(nx - 1) + " 0 " + std::to_string(ny - 1) + " 0 0";
  std::string text;
  text.reserve(std::size_t(nx) * ny * 24 + 1024);
  text += "<?xml version=\"1.0\"?>\n";
  text += "<VTKFile type=\"ImageData\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n";
  text += "  <ImageData WholeExtent=\"" + extent + "\" Origin=\"" + number(x0 + 0.5 * cell) + " " +
          number(y0 + 0.5 * cell) + " 0\" Spacing=\"" + number(cell) + " " + number(cell) + " " + number(cell) +
          "\">\n";
  text += "    <Piece Extent=\"" + extent + "\">\n";
  text += "      <PointData Scalars=\"height\">\n";
  text += "        <DataArray type=\"Float64\" Name=\"height\" format=\"ascii\" NumberOfComponents=\"1\">\n";
  const std::size_t count = std::size_t(nx) * ny;
  for (std::size_t i = 0; i < count; ++i) {
    text += (i % 8 == 0) ? "          " : " ";
    text += number(h[i]);
    if (i % 8 == 7 || i + 1 == count) text += '\n';
  }
  text += "        </DataArray>\n      </PointData>\n      <CellData>\n      </CellData>\n";
  text += "    </Piece>\n  </ImageData>\n</VTKFile>\n";
  write_atomic(path, text);
}
