#include "depth_profile.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

#include "clipped_sphere.hpp"
#include "layer_metrics.hpp"

namespace sm = spreadmap;
using sm::layer::PeriodicStrip;
using sm::layer::SphereArrays;
using sm::layer::undefined;

namespace {

constexpr double max_slices = 1e6;  // beyond this: a unit mistake in the slice, not a bed

// Top of the highest sphere whose disk reaches the region (in y through any periodic image), not
// below `floor`.
double highest_top(const SphereArrays &s, const double region[4], const PeriodicStrip &strip, double floor) {
  double top = floor;
  for (std::size_t i = 0; i < s.n; ++i) {
    const double r = s.r[i];
    if (s.x[i] + r <= region[0] || s.x[i] - r >= region[1]) continue;
    if (!strip.active() && (s.y[i] + r <= region[2] || s.y[i] - r >= region[3])) continue;
    top = std::max(top, s.z[i] + r);
  }
  return top;
}

double solid_volume_in_slab(const SphereArrays &s, const double region[4], const PeriodicStrip &strip, double z_lo,
                            double z_hi) {
  return z_hi > z_lo ? sm::layer::solid_volume_in_slices(s, region, strip, z_lo, z_hi - z_lo, 1)[0] : 0.0;
}

}  // namespace

double sm::layer::sphere_volume_in_box(double xc, double yc, double zc, double r, const double box[6]) {
  const double x0 = box[0], x1 = box[1], y0 = box[2], y1 = box[3], z0 = box[4], z1 = box[5];
  if (r <= 0 || zc + r <= z0 || zc - r >= z1) return 0;
  const bool inside_x = xc - r >= x0 && xc + r <= x1, inside_y = yc - r >= y0 && yc + r <= y1;
  if (zc - r >= z0 && zc + r <= z1) return sphere_volume_in_prism(xc, yc, r, x0, x1, y0, y1);
  // Crossing a horizontal plane: clip by z and by whichever vertical pair the sphere crosses.
  if (inside_x) return sphere_volume_in_prism(yc, zc, r, y0, y1, z0, z1);
  if (inside_y) return sphere_volume_in_prism(xc, zc, r, x0, x1, z0, z1);
  const double share = (unit_sphere_cap_volume((z0 - zc) / r) - unit_sphere_cap_volume((z1 - zc) / r)) /
                       (4 * std::numbers::pi / 3);  // corner sphere: see the header
  return sphere_volume_in_prism(xc, yc, r, x0, x1, y0, y1) * share;
}

std::vector<double> sm::layer::solid_volume_in_slices(const SphereArrays &s, const double region[4],
                                                      const PeriodicStrip &strip, double z0, double dz, std::size_t n) {
  std::vector<double> volume(n, 0.0);
  if (n == 0 || !(dz > 0)) return volume;
  const double z_end = z0 + static_cast<double>(n) * dz;
  for (std::size_t i = 0; i < s.n; ++i) {
    const double r = s.r[i], z = s.z[i];
    if (s.x[i] + r <= region[0] || s.x[i] - r >= region[1] || z + r <= z0 || z - r >= z_end) continue;
    const auto slice_of = [&](double height) {
      return static_cast<std::size_t>(std::clamp(std::floor((height - z0) / dz), 0.0, static_cast<double>(n - 1)));
    };
    const std::size_t k_lo = slice_of(z - r), k_hi = slice_of(z + r);
    for_each_image_shift(s.y[i], r, region[2], region[3], strip, [&](double shift) {
      for (std::size_t k = k_lo; k <= k_hi; ++k) {
        const double box[6] = {region[0],
                               region[1],
                               region[2],
                               region[3],
                               z0 + static_cast<double>(k) * dz,
                               z0 + static_cast<double>(k + 1) * dz};
        volume[k] += sphere_volume_in_box(s.x[i], s.y[i] + shift, z, r, box);
      }
    });
  }
  return volume;
}

sm::layer::DepthProfile sm::layer::depth_profile(const SphereArrays &s, const double region[4],
                                                 const PeriodicStrip &strip, double substrate_z, double mean_height,
                                                 const DepthSettings &settings) {
  if (!(settings.slice > 0) || !std::isfinite(settings.slice))
    throw std::invalid_argument("depth_slice = " + std::to_string(settings.slice) + " m must be > 0");
  if (!(settings.top_thickness >= 0) || !std::isfinite(settings.top_thickness))
    throw std::invalid_argument("top_thickness = " + std::to_string(settings.top_thickness) + " m must be >= 0");
  DepthProfile p;
  p.slice = settings.slice;
  p.top_thickness = settings.top_thickness > 0 ? settings.top_thickness : 2 * mean_diameter(s);
  const double slices =
      std::ceil((highest_top(s, region, strip, substrate_z) - substrate_z) / p.slice - 1e-9);  // round-off
  if (slices > max_slices)
    throw std::invalid_argument("depth_slice = " + std::to_string(p.slice) + " m makes " + std::to_string(slices) +
                                " slices (at most 1e6): give a thicker slice");
  const std::size_t n = static_cast<std::size_t>(slices);
  const double area = (region[1] - region[0]) * (region[3] - region[2]);
  const auto volume = solid_volume_in_slices(s, region, strip, substrate_z, p.slice, n);
  for (std::size_t i = 0; i < n; ++i) {
    p.z.push_back((static_cast<double>(i) + 0.5) * p.slice);
    p.packing.push_back(volume[i] / (area * p.slice));
  }
  const double H = mean_height, t = p.top_thickness;
  if (!(H > 0) || !(t > 0)) {
    p.packing_top = p.packing_bulk = undefined;
    return p;
  }
  const double below = std::max(0.0, H - t);
  p.packing_top = solid_volume_in_slab(s, region, strip, substrate_z + below, substrate_z + H) / (area * (H - below));
  p.packing_bulk =
      H > t ? solid_volume_in_slab(s, region, strip, substrate_z, substrate_z + H - t) / (area * (H - t)) : undefined;
  return p;
}
