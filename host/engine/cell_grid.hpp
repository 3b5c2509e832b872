// Spatial binning for the neighbour search: cells at least as wide as the largest interaction
// reach (largest diameter + skin). Periodic axes span the domain exactly (a whole number of
// cells); open axes span only the particles' bounding box, so a tall, mostly empty domain costs
// no memory.
#pragma once
#include <engine/domain.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>

namespace spreadmap::engine {

template <class Real> struct CellGrid {
  Real origin[3]{0, 0, 0};
  Real inv_size[3]{1, 1, 1};
  int n[3]{1, 1, 1};
  bool periodic[3]{false, false, false};
  // Axes from the fastest-varying in the cell index to the slowest: the axis with the most cells is
  // the slowest, so that neighbouring cells (and the particles sorted by cell) lie close in memory.
  int order[3]{0, 1, 2};

  std::size_t count() const { return std::size_t(n[0]) * n[1] * n[2]; }
  int coord(int axis, Real v) const {
    const int c = static_cast<int>(std::floor((v - origin[axis]) * inv_size[axis]));
    return std::clamp(c, 0, n[axis] - 1);
  }
  std::size_t index(const int c[3]) const {
    return (std::size_t(c[order[2]]) * n[order[1]] + c[order[1]]) * n[order[0]] + c[order[0]];
  }
  void coords(std::size_t cell, int c[3]) const {
    c[order[0]] = int(cell % n[order[0]]);
    c[order[1]] = int((cell / n[order[0]]) % n[order[1]]);
    c[order[2]] = int(cell / (std::size_t(n[order[0]]) * n[order[1]]));
  }
  std::uint32_t cell_of(Real x, Real y, Real z) const {
    const int c[3] = {coord(0, x), coord(1, y), coord(2, z)};
    return static_cast<std::uint32_t>(index(c));
  }
};

// bbox_lo/hi: the particles' bounding box; reach: the largest r_i + r_j + skin; n_particles bounds
// the cell count (at most ~8 cells per particle: sparse scenes get coarser cells, never more memory).
template <class Real>
CellGrid<Real> make_cell_grid(const Domain &domain, const double bbox_lo[3], const double bbox_hi[3], double reach,
                              std::size_t n_particles) {
  double width = reach;
  const double max_cells = 8.0 * double(n_particles) + 64.0;
  CellGrid<Real> g;
  for (int pass = 0; pass < 40; ++pass) {
    double cells = 1;
    for (int a = 0; a < 3; ++a) {
      g.periodic[a] = domain.periodic[a];
      if (domain.periodic[a]) {
        const double length = domain.length(a);
        g.n[a] = std::max(1, static_cast<int>(std::floor(length / width)));
        g.origin[a] = Real(domain.lo[a]);
        g.inv_size[a] = Real(g.n[a] / length);
      } else {
        const double extent = std::max(0.0, bbox_hi[a] - bbox_lo[a]);
        g.n[a] = std::max(1, static_cast<int>(std::floor(extent / width)) + 1);
        g.origin[a] = Real(bbox_lo[a]);
        g.inv_size[a] = Real(1.0 / width);
      }
      cells *= g.n[a];
    }
    if (cells <= max_cells) break;
    width *= std::cbrt(cells / max_cells) * 1.01;
  }
  std::stable_sort(g.order, g.order + 3, [&](int a, int b) { return g.n[a] < g.n[b]; });
  return g;
}

}  // namespace spreadmap::engine
