#include "workflow/calibrate/angle_fit.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <stdexcept>
#include <string>

#include <fmt/format.h>

namespace spreadmap::calibrate {
namespace {

constexpr double degrees = 180.0 / 3.14159265358979323846;

// Highest surface point per bin: bin index -> (bin centre, height).
using Surface = std::map<long, double>;

void raise(Surface &surface, long bin, double height) {
  auto [it, fresh] = surface.emplace(bin, height);
  if (!fresh) it->second = std::max(it->second, height);
}

// Least-squares slope of h against u over the points; NaN with fewer than 3.
double slope(const std::vector<double> &u, const std::vector<double> &h) {
  const std::size_t n = u.size();
  if (n < 3) return std::numeric_limits<double>::quiet_NaN();
  const double mu = std::accumulate(u.begin(), u.end(), 0.0) / double(n);
  const double mh = std::accumulate(h.begin(), h.end(), 0.0) / double(n);
  double suh = 0, suu = 0;
  for (std::size_t k = 0; k < n; ++k) {
    suh += (u[k] - mu) * (h[k] - mh);
    suu += (u[k] - mu) * (u[k] - mu);
  }
  return suu > 0 ? suh / suu : std::numeric_limits<double>::quiet_NaN();
}

AngleFit summarise(std::vector<double> parts, std::size_t points) {
  AngleFit fit;
  fit.points = points;
  const double n = double(parts.size());
  fit.angle_deg = std::accumulate(parts.begin(), parts.end(), 0.0) / n;
  double ss = 0;
  for (double a : parts) ss += (a - fit.angle_deg) * (a - fit.angle_deg);
  fit.spread_deg = parts.size() > 1 ? std::sqrt(ss / (n - 1)) : 0.0;
  fit.uncertainty_deg = fit.spread_deg / std::sqrt(n);
  fit.parts_deg = std::move(parts);
  return fit;
}

double mean_diameter(const engine::ParticleSet &s) {
  if (s.size() == 0) throw std::runtime_error("angle of the surface: the state holds no particles");
  return 2 * std::accumulate(s.radius.begin(), s.radius.end(), 0.0) / double(s.size());
}

}  // namespace

AngleFit heap_angle(const engine::ParticleSet &s, double base_z, int sectors) {
  if (sectors < 3) throw std::invalid_argument("heap_angle: sectors must be >= 3");
  const double bin = 2 * mean_diameter(s);
  double cx = 0, cy = 0;
  for (std::size_t i = 0; i < s.size(); ++i) cx += s.x[i], cy += s.y[i];
  cx /= double(s.size());
  cy /= double(s.size());

  // Top height per square column (equal areas: the maximum's upward bias is the same everywhere).
  std::map<std::pair<long, long>, double> columns;
  double peak = 0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    const double h = s.z[i] + s.radius[i] - base_z;
    const std::pair<long, long> key{long(std::floor((s.x[i] - cx) / bin)), long(std::floor((s.y[i] - cy) / bin))};
    auto [it, fresh] = columns.emplace(key, h);
    if (!fresh) it->second = std::max(it->second, h);
    peak = std::max(peak, h);
  }
  std::vector<std::vector<double>> rho(static_cast<std::size_t>(sectors)), height(rho.size());
  for (const auto &[key, h] : columns) {
    if (h < 0.2 * peak || h > 0.8 * peak) continue;  // the flank only
    const double dx = (double(key.first) + 0.5) * bin, dy = (double(key.second) + 0.5) * bin;
    const double turn = std::atan2(dy, dx) / (2 * 3.14159265358979323846) + 0.5;  // [0, 1]
    const auto k = static_cast<std::size_t>(std::min(sectors - 1, int(turn * sectors)));
    rho[k].push_back(std::hypot(dx, dy));
    height[k].push_back(h);
  }
  std::vector<double> parts;
  std::size_t points = 0;
  for (std::size_t k = 0; k < rho.size(); ++k) {
    const double m = slope(rho[k], height[k]);
    if (!std::isfinite(m))
      throw std::runtime_error(
          fmt::format("angle of repose: sector {} of {} has {} surface columns on the flank (need 3): {} particles, "
                      "heap height {:.3g} m over the plate at z = {:.3g} m; use more particles or a smaller lift speed",
                      k + 1, sectors, rho[k].size(), s.size(), peak, base_z));
    parts.push_back(std::atan(-m) * degrees);
    points += rho[k].size();
  }
  return summarise(std::move(parts), points);
}

AngleFit bed_angle(const engine::ParticleSet &s, int slabs) {
  if (slabs < 1) throw std::invalid_argument("bed_angle: slabs must be >= 1");
  const double bin = 2 * mean_diameter(s);
  const auto [ylo, yhi] = std::minmax_element(s.y.begin(), s.y.end());
  const double width = std::max(*yhi - *ylo, 1e-300);
  std::vector<Surface> surface(static_cast<std::size_t>(slabs));
  for (std::size_t i = 0; i < s.size(); ++i) {
    const int slab = std::min(slabs - 1, int((s.y[i] - *ylo) / width * slabs));
    raise(surface[std::size_t(slab)], long(std::floor(s.x[i] / bin)), s.z[i] + s.radius[i]);
  }
  std::vector<double> parts;
  std::size_t points = 0;
  for (int k = 0; k < slabs; ++k) {
    const Surface &line = surface[std::size_t(k)];
    if (line.empty())
      throw std::runtime_error(fmt::format("drum angle: slab {} of {} holds no particle", k + 1, slabs));
    const double lo = double(line.begin()->first), hi = double(line.rbegin()->first) + 1;
    std::vector<double> u, h;
    for (const auto &[b, height] : line) {
      const double f = (double(b) + 0.5 - lo) / (hi - lo);
      if (f >= 0.2 && f <= 0.8) u.push_back((double(b) + 0.5) * bin), h.push_back(height);
    }
    const double m = slope(u, h);
    if (!std::isfinite(m))
      throw std::runtime_error(
          fmt::format("drum angle: slab {} of {} has {} surface bins in the middle of the bed (need 3); fill the drum "
                      "with more particles",
                      k + 1, slabs, u.size()));
    parts.push_back(std::atan(std::abs(m)) * degrees);
    points += u.size();
  }
  return summarise(std::move(parts), points);
}

AngleFit pooled(const std::vector<AngleFit> &fits) {
  std::vector<double> parts;
  std::size_t points = 0;
  for (const auto &f : fits) parts.insert(parts.end(), f.parts_deg.begin(), f.parts_deg.end()), points += f.points;
  if (parts.empty()) throw std::invalid_argument("pooled: no fits");
  return summarise(std::move(parts), points);
}

}  // namespace spreadmap::calibrate
