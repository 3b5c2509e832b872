#include "resting.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace spreadmap::layer {

std::vector<std::uint8_t> resting_spheres(const SphereArrays &s, double substrate_z, const PeriodicStrip &strip,
                                          double tolerance, const std::uint8_t *ground) {
  const std::size_t n = s.n;
  std::vector<std::uint8_t> resting(n, 0);
  if (n == 0) return resting;
  double r_max = 0, x_lo = s.x[0], x_hi = s.x[0], y_lo = s.y[0], y_hi = s.y[0];
  for (std::size_t i = 0; i < n; ++i) {
    r_max = std::max(r_max, s.r[i]);
    x_lo = std::min(x_lo, s.x[i]), x_hi = std::max(x_hi, s.x[i]);
    y_lo = std::min(y_lo, s.y[i]), y_hi = std::max(y_hi, s.y[i]);
  }
  // x-y columns at least one reach wide: a touching pair is in the same or a neighbouring column
  const double reach = 2 * r_max * (1 + tolerance);
  if (!(reach > 0)) return resting;
  const bool periodic = strip.active();
  const double period = strip.period();
  if (periodic) y_lo = std::min(strip.lo, strip.hi), y_hi = y_lo + period;
  const auto cells = [&](double extent) { return std::max<std::int64_t>(1, std::int64_t(extent / reach)); };
  const std::int64_t nx = cells(x_hi - x_lo), ny = cells(y_hi - y_lo);
  const double cx = std::max(reach, (x_hi - x_lo) / double(nx)), cy = std::max(reach, (y_hi - y_lo) / double(ny));
  auto column = [&](std::size_t i) {
    const std::int64_t ix = std::clamp<std::int64_t>(std::int64_t((s.x[i] - x_lo) / cx), 0, nx - 1);
    double y = s.y[i];
    if (periodic) y = y_lo + (y - y_lo) - std::floor((y - y_lo) / period) * period;
    const std::int64_t iy = std::clamp<std::int64_t>(std::int64_t((y - y_lo) / cy), 0, ny - 1);
    return iy * nx + ix;
  };
  std::vector<std::uint32_t> start(std::size_t(nx * ny) + 1, 0), member(n);
  std::vector<std::int64_t> col(n);
  for (std::size_t i = 0; i < n; ++i) ++start[std::size_t((col[i] = column(i))) + 1];
  for (std::size_t c = 1; c < start.size(); ++c) start[c] += start[c - 1];
  {
    std::vector<std::uint32_t> next(start.begin(), start.end() - 1);
    for (std::size_t i = 0; i < n; ++i) member[next[std::size_t(col[i])]++] = std::uint32_t(i);
  }
  std::vector<std::uint32_t> queue;
  for (std::size_t i = 0; i < n; ++i)
    if ((ground && ground[i]) || s.z[i] - s.r[i] <= substrate_z + 2 * s.r[i] * tolerance)
      resting[i] = 1, queue.push_back(std::uint32_t(i));
  // Breadth-first over touching pairs from the spheres on the substrate.
  for (std::size_t head = 0; head < queue.size(); ++head) {
    const std::uint32_t i = queue[head];
    const std::int64_t ix = col[i] % nx, iy = col[i] / nx;
    for (std::int64_t dy = -1; dy <= 1; ++dy) {
      std::int64_t qy = iy + dy;
      if (periodic) qy = (qy + ny) % ny;  // with fewer than 3 columns one may come twice: harmless
      else if (qy < 0 || qy >= ny) continue;
      for (std::int64_t qx = std::max<std::int64_t>(0, ix - 1); qx <= std::min(nx - 1, ix + 1); ++qx) {
        const std::size_t c = std::size_t(qy * nx + qx);
        for (std::uint32_t k = start[c]; k < start[c + 1]; ++k) {
          const std::uint32_t j = member[k];
          if (resting[j]) continue;
          double dyv = s.y[i] - s.y[j];
          if (periodic) dyv -= period * std::round(dyv / period);
          const double dxv = s.x[i] - s.x[j], dzv = s.z[i] - s.z[j];
          const double touch = (s.r[i] + s.r[j]) * (1 + tolerance);
          if (dxv * dxv + dyv * dyv + dzv * dzv <= touch * touch) resting[j] = 1, queue.push_back(j);
        }
      }
    }
  }
  return resting;
}

}  // namespace spreadmap::layer
