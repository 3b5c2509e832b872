#include "powder/heap.hpp"

#include <algorithm>
#include <cmath>
#include <functional>

#include <fmt/format.h>
#include <spreadmap/sphere.hpp>

namespace spreadmap::powder {
namespace {

// Uniform cells of at least the largest diameter over the region (x, y fixed; z grows with the
// top), each listing the spheres whose centre lies in it: two spheres can only overlap when their
// cells are neighbours.
class PlacementGrid {
 public:
  PlacementGrid(const Box &region, bool periodic_y, double cell, double top)
      : x0_(region.lo[0]),
        y0_(region.lo[1]),
        z0_(region.lo[2]),
        width_(region.hi[1] - region.lo[1]),
        cell_(cell),
        periodic_y_(periodic_y) {
    nx_ = std::max(1L, static_cast<long>(std::ceil((region.hi[0] - x0_) / cell)));
    // Periodic: a whole number of cells no smaller than `cell` spans the strip exactly.
    ny_ = periodic_y ? std::max(1L, static_cast<long>(std::floor(width_ / cell)))
                     : std::max(1L, static_cast<long>(std::ceil(width_ / cell)));
    cell_y_ = periodic_y ? width_ / static_cast<double>(ny_) : cell;
    grow_to(top);
  }

  void grow_to(double top) {
    const long nz = std::max(1L, static_cast<long>(std::ceil((top - z0_) / cell_)));
    if (nz > nz_) {
      nz_ = nz;
      cells_.resize(static_cast<std::size_t>(nx_ * ny_ * nz_));
    }
  }

  void add(std::uint32_t i, double x, double y, double z) { cells_[index(ix(x), iy(y), iz(z))].push_back(i); }

  bool overlaps(double x, double y, double z, double r, const Heap &heap) const {
    const long cx = ix(x), cy = iy(y), cz = iz(z);
    long y_cells[3];
    int n_y = 0;
    if (periodic_y_ && ny_ < 3) {
      for (long j = 0; j < ny_; ++j) y_cells[n_y++] = j;
    } else {
      for (long j = cy - 1; j <= cy + 1; ++j) {
        if (periodic_y_) y_cells[n_y++] = (j + ny_) % ny_;
        else if (j >= 0 && j < ny_) y_cells[n_y++] = j;
      }
    }
    for (long k = std::max(0L, cz - 1); k <= std::min(nz_ - 1, cz + 1); ++k)
      for (int jj = 0; jj < n_y; ++jj)
        for (long i = std::max(0L, cx - 1); i <= std::min(nx_ - 1, cx + 1); ++i)
          for (std::uint32_t other : cells_[index(i, y_cells[jj], k)]) {
            const double dx = x - heap.x[other], dz = z - heap.z[other];
            double dy = y - heap.y[other];
            if (periodic_y_) dy -= width_ * std::round(dy / width_);
            const double contact = r + heap.r[other];
            if (dx * dx + dy * dy + dz * dz < contact * contact) return true;
          }
    return false;
  }

 private:
  long ix(double x) const { return std::clamp(static_cast<long>(std::floor((x - x0_) / cell_)), 0L, nx_ - 1); }
  long iy(double y) const { return std::clamp(static_cast<long>(std::floor((y - y0_) / cell_y_)), 0L, ny_ - 1); }
  long iz(double z) const { return std::clamp(static_cast<long>(std::floor((z - z0_) / cell_)), 0L, nz_ - 1); }
  std::size_t index(long i, long j, long k) const { return static_cast<std::size_t>((k * ny_ + j) * nx_ + i); }

  double x0_, y0_, z0_, width_, cell_, cell_y_ = 0;
  bool periodic_y_;
  long nx_ = 1, ny_ = 1, nz_ = 0;
  std::vector<std::vector<std::uint32_t>> cells_;
};

bool inside_cylinder(const CylinderY &c, double x, double y, double z, double r) {
  const double radial = std::hypot(x - c.x, z - c.z) - c.radius;
  const double axial = std::max(c.y_lo - y, y - c.y_hi);
  const double distance = (radial > 0 && axial > 0) ? std::hypot(radial, axial) : std::max(radial, axial);
  return distance < r;
}

bool inside_box(const Box &b, double x, double y, double z, double r) {
  const double p[3] = {x, y, z};
  double d2 = 0;
  for (int a = 0; a < 3; ++a) {
    const double gap = std::max({b.lo[a] - p[a], 0.0, p[a] - b.hi[a]});
    d2 += gap * gap;
  }
  return d2 < r * r;
}

bool excluded(const HeapSpec &spec, double x, double y, double z, double r) {
  for (const auto &c : spec.excluded_cylinders)
    if (inside_cylinder(c, x, y, z, r)) return true;
  for (const auto &b : spec.excluded_boxes)
    if (inside_box(b, x, y, z, r)) return true;
  return spec.excluded && spec.excluded(x, y, z, r);
}

void check(const HeapSpec &spec) {
  for (int a = 0; a < 3; ++a)
    if (!(spec.region.lo[a] < spec.region.hi[a]))
      throw PowderError(fmt::format("heap region: lo = {} m must be below hi = {} m along {}", spec.region.lo[a],
                                   spec.region.hi[a], "xyz"[a]));
  if ((spec.count > 0) == (spec.solid_volume > 0))
    throw PowderError(
        fmt::format("heap: give either a particle count or a solid volume, not {} (count {}, volume {} m^3)",
                    spec.count > 0 ? "both" : "neither", spec.count, spec.solid_volume));
  if (spec.attempts_per_sphere == 0) throw PowderError("heap: attempts_per_sphere must be at least 1");
  spec.sizes.validate();
  const double d = spec.sizes.upper();
  const double span_x = spec.region.hi[0] - spec.region.lo[0], span_y = spec.region.hi[1] - spec.region.lo[1];
  if (span_x < d || span_y < d)
    throw PowderError(
        fmt::format("heap region: {} m x {} m (x, y) cannot hold a sphere of diameter {} m", span_x, span_y, d));
}

}  // namespace

std::size_t heap_volume_to_count(double solid_volume, const SizeDistribution &sizes) {
  sizes.validate();
  if (!(solid_volume > 0)) throw PowderError(fmt::format("heap: solid volume {} m^3 must be > 0", solid_volume));
  const double n = std::round(solid_volume / sizes.mean_sphere_volume());
  return static_cast<std::size_t>(std::max(1.0, n));
}

Heap insert_heap(const HeapSpec &spec) {
  check(spec);
  const std::size_t n = spec.count > 0 ? spec.count : heap_volume_to_count(spec.solid_volume, spec.sizes);
  if (n > 0xffffffffu) throw PowderError(fmt::format("heap: {} particles exceed the 2^32 limit", n));
  Random random(spec.seed);
  std::vector<double> diameters = spec.sizes.sample(n, random);
  std::sort(diameters.begin(), diameters.end(), std::greater<>());  // largest first

  const Box &box = spec.region;
  const double largest = spec.sizes.upper(), width = box.hi[1] - box.lo[1];
  Heap heap;
  heap.top = std::min(box.hi[2], spec.max_top);
  heap.x.reserve(n);
  heap.y.reserve(n);
  heap.z.reserve(n);
  heap.r.reserve(n);
  PlacementGrid grid(box, spec.periodic_y, largest, heap.top);

  auto grow = [&](std::size_t placed, double r) {
    if (heap.top >= spec.max_top) {
      const double box_volume = (box.hi[0] - box.lo[0]) * width * (heap.top - box.lo[2]);
      throw PowderError(fmt::format(
          "heap: placed {} of {} spheres (diameters {:.4g} to {:.4g} m; the next has {:.4g} m) in x [{:.4g}, {:.4g}] "
          "m, "
          "y [{:.4g}, {:.4g}] m, z [{:.4g}, {:.4g}] m (solid fraction {:.3f} of that box, exclusions included); "
          "it is full and may not grow above max_top = {:.4g} m: enlarge the region, raise max_top or insert fewer "
          "particles (random sequential addition jams near a solid fraction of 0.38)",
          placed, n, spec.sizes.lower(), largest, 2 * r, box.lo[0], box.hi[0], box.lo[1], box.hi[1], box.lo[2],
          heap.top, heap.solid_volume / box_volume, spec.max_top));
    }
    heap.top = std::min(heap.top + largest, spec.max_top);
    grid.grow_to(heap.top);
  };

  for (std::size_t i = 0; i < n; ++i) {
    const double r = 0.5 * diameters[i];
    std::size_t failures = 0;
    for (;;) {
      if (heap.top - box.lo[2] < 2 * r) {
        grow(i, r);
        continue;
      }
      const double x = random.uniform(box.lo[0] + r, box.hi[0] - r);
      double y = spec.periodic_y ? random.uniform(box.lo[1], box.hi[1]) : random.uniform(box.lo[1] + r, box.hi[1] - r);
      if (spec.periodic_y && y >= box.hi[1]) y -= width;  // rounding at the upper end
      const double z = random.uniform(box.lo[2] + r, heap.top - r);
      ++heap.attempts;
      if (!excluded(spec, x, y, z, r) && !grid.overlaps(x, y, z, r, heap)) {
        grid.add(static_cast<std::uint32_t>(i), x, y, z);
        heap.x.push_back(x);
        heap.y.push_back(y);
        heap.z.push_back(z);
        heap.r.push_back(r);
        heap.solid_volume += sphere_volume(diameters[i]);
        break;
      }
      if (++failures >= spec.attempts_per_sphere) {
        grow(i, r);
        failures = 0;
      }
    }
  }
  return heap;
}

}  // namespace spreadmap::powder
