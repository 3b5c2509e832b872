// Height map of a layer of spheres: h(x, y) = top of the highest sphere surface above each grid point,
// measured above the substrate plane, 0 on bare substrate.
//
// The grid has square cells of side `cell`; per axis the region's extent is divided into
// round(extent / cell) cells (at least one), and the grid is centred on the region, so it covers the
// region exactly when the cell divides its extent. h is sampled at the cell centres. A point is covered
// when its horizontal distance to a sphere's centre is <= the radius; spheres centred outside the
// region count, and in a periodic strip across y so do their periodic images. Spheres are binned in
// 2-D first, so the cost grows linearly with particles and grid points. SI units.
#pragma once
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace spreadmap::layer {

// Centres and radii [m], structure of arrays, borrowed.
struct SphereArrays {
  std::size_t n = 0;
  const double *x = nullptr, *y = nullptr, *z = nullptr, *r = nullptr;
};

// A periodic strip across y: images of every sphere at y + k (hi - lo). Inactive when lo == hi.
struct PeriodicStrip {
  double lo = 0, hi = 0;
  bool active() const { return hi != lo; }
  double period() const { return hi > lo ? hi - lo : lo - hi; }
};

// Sampling grid: nx * ny square cells of side `cell`; (x0, y0) is the lower-left corner of cell (0, 0),
// whose centre is (x0 + cell/2, y0 + cell/2). Row-major storage: index iy * nx + ix.
struct Grid {
  std::uint32_t nx = 0, ny = 0;
  double x0 = 0, y0 = 0, cell = 0;
  double x_centre(std::uint32_t ix) const { return x0 + (ix + 0.5) * cell; }
  double y_centre(std::uint32_t iy) const { return y0 + (iy + 0.5) * cell; }
  std::size_t size() const { return std::size_t(nx) * ny; }
};

// round(extent / cell) cells per axis (at least 1), centred on the region x0, x1, y0, y1.
// Throws std::invalid_argument for an empty or inverted region, a non-positive cell, or a grid too
// large to hold in memory.
Grid make_grid(const double region[4], double cell);

// Heights above substrate_z at every grid point [m], row-major. Parallel over grid rows (OpenMP);
// the result does not depend on the thread count. A sphere whose top lies below the substrate
// leaves h = 0. `covered` (optional) receives 1 where some sphere covers the point, else 0.
std::vector<double> compute_heightmap(const SphereArrays &spheres, const Grid &grid, double substrate_z,
                                      const PeriodicStrip &strip, std::vector<std::uint8_t> *covered = nullptr);

// The shifts k * period (k integer) that bring a sphere centred at y with radius r to overlap
// [lo, hi] in y; just {0} when the strip is inactive. Calls visit(shift) for each.
template <class Visit>
void for_each_image_shift(double y, double r, double lo, double hi, const PeriodicStrip &strip, Visit &&visit) {
  if (!strip.active()) {
    visit(0.0);
    return;
  }
  const double L = strip.period();
  const long k_lo = static_cast<long>(std::ceil((lo - r - y) / L));
  const long k_hi = static_cast<long>(std::floor((hi + r - y) / L));
  for (long k = k_lo; k <= k_hi; ++k) visit(k * L);
}

}  // namespace spreadmap::layer
