// Writes a height map as a VTK ImageData XML file (.vti, ASCII), for ParaView and the figures.
// Plain C++, no VTK dependency. The file is written to a temporary name and renamed (write_atomic).
#pragma once
#include <cstdint>
#include <filesystem>

namespace spreadmap {

// h: nx * ny heights [m], row-major (iy * nx + ix), as returned by a metrics plugin's heightmap().
// (x0, y0): lower-left corner of the grid [m]; samples sit at cell centres x0 + (ix + 1/2) cell, so
// the file's Origin is (x0 + cell/2, y0 + cell/2, 0) and its Spacing (cell, cell, cell). The scalar
// point array is named "height". Throws std::invalid_argument for an empty map or a non-positive cell,
// RunFailure when the file cannot be written.
void write_heightmap_vti(const std::filesystem::path &path, std::uint32_t nx, std::uint32_t ny, double x0, double y0,
                         double cell, const double *h);

}  // namespace spreadmap
