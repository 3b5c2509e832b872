#include "heightmap.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace sm = spreadmap;
using sm::layer::Grid;

namespace {

// Beyond this the map alone would take gigabytes: a unit mistake in `grid` or the region, not a layer.
constexpr double max_grid_points = 2e8;

std::uint32_t cells_along(double extent, double cell) {
  return static_cast<std::uint32_t>(std::max(1.0, std::round(extent / cell)));
}

// Sphere images that can touch the grid, sorted by 2-D bin (compressed rows: bin b holds
// [start[b], start[b+1])). Bins are at least as large as the largest radius, so a grid point finds
// every sphere that may cover it in the 3 x 3 bins around it.
struct BinnedSpheres {
  double x0 = 0, y0 = 0, size = 1, r_max = 0;
  long nbx = 0, nby = 0;
  std::vector<std::size_t> start;
  std::vector<double> x, y, top, r2;  // top: centre height above the substrate

  long bin_x(double px) const { return std::clamp(static_cast<long>(std::floor((px - x0) / size)), 0L, nbx - 1); }
  long bin_y(double py) const { return std::clamp(static_cast<long>(std::floor((py - y0) / size)), 0L, nby - 1); }
};

struct Image {
  double x, y, top, r;
};

BinnedSpheres bin_spheres(const sm::layer::SphereArrays &s, const Grid &g, double substrate_z,
                          const sm::layer::PeriodicStrip &strip) {
  // Sample points span [lo, hi] per axis; a sphere matters only if its disk reaches that span.
  const double gx_lo = g.x_centre(0), gx_hi = g.x_centre(g.nx - 1);
  const double gy_lo = g.y_centre(0), gy_hi = g.y_centre(g.ny - 1);
  std::vector<Image> images;
  images.reserve(s.n);
  for (std::size_t i = 0; i < s.n; ++i) {
    const double r = s.r[i];
    if (!(r > 0) || s.x[i] + r < gx_lo || s.x[i] - r > gx_hi) continue;
    sm::layer::for_each_image_shift(s.y[i], r, gy_lo, gy_hi, strip, [&](double shift) {
      const double y = s.y[i] + shift;
      if (y + r >= gy_lo && y - r <= gy_hi) images.push_back({s.x[i], y, s.z[i] - substrate_z, r});
    });
  }

  BinnedSpheres b;
  for (const Image &im : images) b.r_max = std::max(b.r_max, im.r);
  b.size = std::max(b.r_max, g.cell);
  b.x0 = gx_lo - b.r_max;
  b.y0 = gy_lo - b.r_max;
  b.nbx = static_cast<long>(std::floor((gx_hi + b.r_max - b.x0) / b.size)) + 1;
  b.nby = static_cast<long>(std::floor((gy_hi + b.r_max - b.y0) / b.size)) + 1;

  // Counting sort by bin: a stable, deterministic order.
  std::vector<std::size_t> bin_of(images.size());
  b.start.assign(static_cast<std::size_t>(b.nbx * b.nby) + 1, 0);
  for (std::size_t k = 0; k < images.size(); ++k) {
    bin_of[k] = static_cast<std::size_t>(b.bin_y(images[k].y) * b.nbx + b.bin_x(images[k].x));
    ++b.start[bin_of[k] + 1];
  }
  for (std::size_t k = 1; k < b.start.size(); ++k) b.start[k] += b.start[k - 1];
  std::vector<std::size_t> fill(b.start.begin(), b.start.end() - 1);
  b.x.resize(images.size());
  b.y.resize(images.size());
  b.top.resize(images.size());
  b.r2.resize(images.size());
  for (std::size_t k = 0; k < images.size(); ++k) {
    const std::size_t slot = fill[bin_of[k]]++;
    b.x[slot] = images[k].x;
    b.y[slot] = images[k].y;
    b.top[slot] = images[k].top;
    b.r2[slot] = images[k].r * images[k].r;
  }
  return b;
}

}  // namespace

Grid sm::layer::make_grid(const double region[4], double cell) {
  const double width = region[1] - region[0], depth = region[3] - region[2];
  if (!(width > 0) || !(depth > 0) || !std::isfinite(width) || !std::isfinite(depth))
    throw std::invalid_argument("sampling region x [" + std::to_string(region[0]) + ", " + std::to_string(region[1]) +
                                "] m, y [" + std::to_string(region[2]) + ", " + std::to_string(region[3]) +
                                "] m is empty or inverted: give x0 < x1 and y0 < y1");
  if (!(cell > 0) || !std::isfinite(cell))
    throw std::invalid_argument("height-map cell " + std::to_string(cell) + " m must be a positive length");
  const double nx = std::max(1.0, std::round(width / cell)), ny = std::max(1.0, std::round(depth / cell));
  if (nx * ny > max_grid_points)
    throw std::invalid_argument("height map of " + std::to_string(nx) + " x " + std::to_string(ny) +
                                " cells is too large: use a coarser grid (cell " + std::to_string(cell) + " m)");
  Grid g;
  g.nx = cells_along(width, cell);
  g.ny = cells_along(depth, cell);
  g.cell = cell;
  g.x0 = 0.5 * (region[0] + region[1]) - 0.5 * g.nx * cell;
  g.y0 = 0.5 * (region[2] + region[3]) - 0.5 * g.ny * cell;
  return g;
}

std::vector<double> sm::layer::compute_heightmap(const SphereArrays &spheres, const Grid &g, double substrate_z,
                                                 const PeriodicStrip &strip, std::vector<std::uint8_t> *covered) {
  std::vector<double> h(g.size(), 0.0);
  if (covered) covered->assign(g.size(), 0);
  if (g.size() == 0) return h;
  const BinnedSpheres b = bin_spheres(spheres, g, substrate_z, strip);
  if (b.x.empty()) return h;
  std::uint8_t *cov = covered ? covered->data() : nullptr;

#pragma omp parallel for schedule(static)
  for (long iy = 0; iy < static_cast<long>(g.ny); ++iy) {
    const double py = g.y_centre(static_cast<std::uint32_t>(iy));
    const long by_lo = b.bin_y(py - b.r_max), by_hi = b.bin_y(py + b.r_max);
    for (std::uint32_t ix = 0; ix < g.nx; ++ix) {
      const double px = g.x_centre(ix);
      const long bx_lo = b.bin_x(px - b.r_max), bx_hi = b.bin_x(px + b.r_max);
      bool hit = false;
      double highest = 0;
      for (long by = by_lo; by <= by_hi; ++by) {
        const std::size_t first = b.start[by * b.nbx + bx_lo], last = b.start[by * b.nbx + bx_hi + 1];
        for (std::size_t k = first; k < last; ++k) {
          const double dx = px - b.x[k], dy = py - b.y[k];
          const double d2 = dx * dx + dy * dy;
          if (d2 > b.r2[k]) continue;
          const double top = b.top[k] + std::sqrt(b.r2[k] - d2);
          highest = hit ? std::max(highest, top) : top;
          hit = true;
        }
      }
      const std::size_t idx = static_cast<std::size_t>(iy) * g.nx + ix;
      h[idx] = hit ? std::max(0.0, highest) : 0.0;
      if (cov) cov[idx] = hit ? 1 : 0;
    }
  }
  return h;
}
