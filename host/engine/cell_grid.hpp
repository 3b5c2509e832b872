// Spatial binning for the neighbour search: cells at least as wide as the largest interaction
// reach (largest diameter + skin). Periodic axes span the domain exactly (a whole number of
// cells); open axes span only the particles' bounding box, so a tall, mostly empty domain costs
// no memory.
#pragma once
#include <engine/domain.hpp>
#include <spreadmap/hd.hpp>

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

  // Host-device: the GPU backend bins with the very same functions.
  SM_HD std::size_t count() const { return std::size_t(n[0]) * n[1] * n[2]; }
  SM_HD int coord(int axis, Real v) const {
    const int c = static_cast<int>(std::floor((v - origin[axis]) * inv_size[axis]));
    return c < 0 ? 0 : (c > n[axis] - 1 ? n[axis] - 1 : c);
  }
  SM_HD std::size_t index(const int c[3]) const {
    return (std::size_t(c[order[2]]) * n[order[1]] + c[order[1]]) * n[order[0]] + c[order[0]];
  }
  SM_HD void coords(std::size_t cell, int c[3]) const {
    c[order[0]] = int(cell % n[order[0]]);
    c[order[1]] = int((cell / n[order[0]]) % n[order[1]]);
    c[order[2]] = int(cell / (std::size_t(n[order[0]]) * n[order[1]]));
  }
  SM_HD std::uint32_t cell_of(Real x, Real y, Real z) const {
    const int c[3] = {coord(0, x), coord(1, y), coord(2, z)};
    return static_cast<std::uint32_t>(index(c));
  }
};

// The particle ranges [begin, end) of the cells around a cell (itself included), each cell once
// (an axis of fewer than three periodic cells wraps onto the same ones), empty ones left out, in
// increasing begin: particles sorted by cell then meet their neighbours in increasing index.
struct CellRanges {
  std::uint32_t begin[27], end[27];
  int n = 0;

  // Adds [b, e) in its place by begin, unless it is empty (ranges of distinct cells never share a begin).
  SM_HD void insert(std::uint32_t b, std::uint32_t e) {
    if (b == e) return;
    int at = n++;
    while (at > 0 && begin[at - 1] > b) {
      begin[at] = begin[at - 1];
      end[at] = end[at - 1];
      --at;
    }
    begin[at] = b;
    end[at] = e;
  }
};

namespace detail {
// Distinct cell coordinates among c-1, c, c+1 along one axis (wrapped when periodic).
SM_HD int axis_neighbours(int c, int n, bool periodic, int out[3]) {
  int k = 0;
  for (int d = -1; d <= 1; ++d) {
    int q = c + d;
    if (periodic) q = (q + n) % n;
    else if (q < 0 || q >= n) continue;
    bool seen = false;
    for (int t = 0; t < k; ++t) seen = seen || out[t] == q;
    if (!seen) out[k++] = q;
  }
  return k;
}
}  // namespace detail

template <class Real>
SM_HD CellRanges neighbour_ranges(const CellGrid<Real> &grid, std::uint32_t cell, const std::uint32_t *cell_start) {
  CellRanges r;
  int cc[3];
  grid.coords(cell, cc);
  int ax[3], ay[3], az[3];
  const int kx = detail::axis_neighbours(cc[0], grid.n[0], grid.periodic[0], ax);
  const int ky = detail::axis_neighbours(cc[1], grid.n[1], grid.periodic[1], ay);
  const int kz = detail::axis_neighbours(cc[2], grid.n[2], grid.periodic[2], az);
  for (int a = 0; a < kz; ++a)
    for (int b = 0; b < ky; ++b)
      for (int c = 0; c < kx; ++c) {
        const int nc[3] = {ax[c], ay[b], az[a]};
        const std::size_t q = grid.index(nc);
        r.insert(cell_start[q], cell_start[q + 1]);
      }
  return r;
}

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
