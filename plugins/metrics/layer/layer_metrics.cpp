#include "layer_metrics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <utility>

#include "clipped_sphere.hpp"
#include "resting.hpp"

namespace sm = spreadmap;
using sm::layer::LayerResult;
using sm::layer::PeriodicStrip;
using sm::layer::SphereArrays;
using sm::layer::undefined;

namespace {

void check_input(const sm_layer_input_v1 &in) {
  if (in.n > 0 && (!in.x || !in.y || !in.z || !in.r))
    throw std::invalid_argument("layer input has " + std::to_string(in.n) + " spheres but a null array");
  for (double v : in.region)
    if (!std::isfinite(v)) throw std::invalid_argument("sampling region has a non-finite bound");
  if (!std::isfinite(in.substrate_z)) throw std::invalid_argument("substrate height is not finite");
  if (!std::isfinite(in.periodic_y[0]) || !std::isfinite(in.periodic_y[1]))
    throw std::invalid_argument("periodic strip bounds are not finite");
  for (std::uint64_t i = 0; i < in.n; ++i)
    if (!std::isfinite(in.x[i]) || !std::isfinite(in.y[i]) || !std::isfinite(in.z[i]) || !std::isfinite(in.r[i]) ||
        in.r[i] < 0)
      throw std::invalid_argument("sphere " + std::to_string(i) + " has a non-finite position or an invalid radius");
}

// Mean and population standard deviation, two passes (one pass loses digits when rq << mean).
void height_moments(const std::vector<double> &h, double &mean, double &stddev) {
  double sum = 0;
  for (double v : h) sum += v;
  mean = sum / static_cast<double>(h.size());
  double sq = 0;
  for (double v : h) sq += (v - mean) * (v - mean);
  stddev = std::sqrt(sq / static_cast<double>(h.size()));
}

nlohmann::ordered_json number_or_null(double v) {
  return std::isfinite(v) ? nlohmann::ordered_json(v) : nlohmann::ordered_json(nullptr);
}

std::string metres(double v) { return std::to_string(v * 1e6) + " um"; }

// Calls visit(i) for every sphere i with a centre (or a periodic image's) in [x0, x1) x [y0, y1).
template <class Visit>
void for_each_centre_in_region(const SphereArrays &s, const double region[4], const PeriodicStrip &strip,
                               Visit &&visit) {
  for (std::size_t i = 0; i < s.n; ++i) {
    if (s.x[i] < region[0] || s.x[i] >= region[1]) continue;
    sm::layer::for_each_image_shift(s.y[i], 0.0, region[2], region[3], strip, [&](double shift) {
      const double y = s.y[i] + shift;
      if (y >= region[2] && y < region[3]) visit(i);
    });
  }
}

}  // namespace

double sm::layer::mean_diameter(const SphereArrays &s) {
  if (s.n == 0) return 0;
  double sum = 0;
  for (std::size_t i = 0; i < s.n; ++i) sum += 2 * s.r[i];
  return sum / static_cast<double>(s.n);
}

double sm::layer::solid_volume_in_region(const SphereArrays &s, const double region[4], const PeriodicStrip &strip) {
  double volume = 0;
  for (std::size_t i = 0; i < s.n; ++i) {
    const double r = s.r[i];
    if (s.x[i] + r <= region[0] || s.x[i] - r >= region[1]) continue;
    for_each_image_shift(s.y[i], r, region[2], region[3], strip, [&](double shift) {
      volume += sphere_volume_in_prism(s.x[i], s.y[i] + shift, r, region[0], region[1], region[2], region[3]);
    });
  }
  return volume;
}

std::uint64_t sm::layer::centres_in_region(const SphereArrays &s, const double region[4], const PeriodicStrip &strip) {
  std::uint64_t count = 0;
  for_each_centre_in_region(s, region, strip, [&](std::size_t) { ++count; });
  return count;
}

std::vector<double> sm::layer::diameters_in_region(const SphereArrays &s, const double region[4],
                                                   const PeriodicStrip &strip) {
  std::vector<double> d;
  for_each_centre_in_region(s, region, strip, [&](std::size_t i) { d.push_back(2 * s.r[i]); });
  return d;
}

std::size_t sm::layer::largest_bare_patch_points(const std::vector<std::uint8_t> &covered, std::uint32_t nx,
                                                 std::uint32_t ny) {
  // Flood fill with an explicit stack: a patch can hold millions of points.
  std::vector<std::uint8_t> seen(covered.size(), 0);
  std::vector<std::size_t> stack;
  std::size_t largest = 0;
  for (std::size_t start = 0; start < covered.size(); ++start) {
    if (covered[start] || seen[start]) continue;
    std::size_t size = 0;
    seen[start] = 1;
    stack.push_back(start);
    while (!stack.empty()) {
      const std::size_t p = stack.back();
      stack.pop_back();
      ++size;
      const std::uint32_t ix = static_cast<std::uint32_t>(p % nx), iy = static_cast<std::uint32_t>(p / nx);
      const auto visit = [&](std::size_t q) {
        if (!covered[q] && !seen[q]) {
          seen[q] = 1;
          stack.push_back(q);
        }
      };
      if (ix > 0) visit(p - 1);
      if (ix + 1 < nx) visit(p + 1);
      if (iy > 0) visit(p - nx);
      if (iy + 1 < ny) visit(p + nx);
    }
    largest = std::max(largest, size);
  }
  return largest;
}

LayerResult sm::layer::characterise_layer(const sm_layer_input_v1 &in, double cell, bool exclude_loose,
                                          bool with_segregation, const DepthSettings *depth_settings) {
  check_input(in);
  LayerResult out;
  SphereArrays spheres{static_cast<std::size_t>(in.n), in.x, in.y, in.z, in.r};
  const PeriodicStrip strip{in.periodic_y[0], in.periodic_y[1]};
  // A rough substrate's spheres are ground the powder rests on, never part of the layer.
  const auto is_substrate = [&](std::size_t i) { return in.substrate && in.substrate[i]; };
  std::size_t substrate_spheres = 0;
  for (std::size_t i = 0; i < spheres.n; ++i) substrate_spheres += is_substrate(i);
  std::vector<double> kept[4];  // the powder's columns, less the loose spheres when those are left out
  if (exclude_loose || substrate_spheres > 0) {
    const auto resting = exclude_loose
                             ? resting_spheres(spheres, in.substrate_z, strip, resting_tolerance, in.substrate)
                             : std::vector<std::uint8_t>(spheres.n, 1);
    for (std::size_t i = 0; i < spheres.n; ++i) {
      if (!resting[i] || is_substrate(i)) continue;
      kept[0].push_back(in.x[i]), kept[1].push_back(in.y[i]), kept[2].push_back(in.z[i]), kept[3].push_back(in.r[i]);
    }
    if (exclude_loose) out.metrics.loose_spheres = spheres.n - substrate_spheres - kept[0].size();
    spheres = {kept[0].size(), kept[0].data(), kept[1].data(), kept[2].data(), kept[3].data()};
    if (out.metrics.loose_spheres > 0)
      out.warnings.push_back(std::to_string(out.metrics.loose_spheres) +
                             " sphere(s) rest on nothing (in flight when the state was taken): left out of the layer");
  }
  const double width = in.region[1] - in.region[0], depth = in.region[3] - in.region[2];

  if (!(cell > 0)) {
    const double d = mean_diameter(spheres);
    if (d > 0) {
      cell = d / 5;
    } else {
      cell = std::min(width, depth) / 100;
      out.warnings.push_back("no spheres in the input: height-map cell set to 1/100 of the region (" + metres(cell) +
                             ") instead of diameter / 5");
    }
  }
  out.grid = make_grid(in.region, cell);
  out.height = compute_heightmap(spheres, out.grid, in.substrate_z, strip, &out.covered);

  LayerMetrics &m = out.metrics;
  m.cell = cell;
  height_moments(out.height, m.mean_height, m.rq);
  m.vs = std::isnan(in.speed) ? undefined : m.mean_height * in.speed;

  const double area = width * depth;
  const double solid = solid_volume_in_region(spheres, in.region, strip);
  m.solid_thickness = solid / area;
  const double map_volume = m.mean_height * area;
  m.packing_fraction = map_volume > 0 ? solid / map_volume : undefined;
  m.packing_fraction_gap = std::isfinite(in.gap) && in.gap > 0 ? solid / (area * in.gap) : undefined;

  const std::size_t n_covered = static_cast<std::size_t>(std::count(out.covered.begin(), out.covered.end(), 1));
  m.coverage = static_cast<double>(n_covered) / static_cast<double>(out.grid.size());
  m.largest_bare_patch =
      static_cast<double>(largest_bare_patch_points(out.covered, out.grid.nx, out.grid.ny)) * cell * cell;
  m.particles_in_region = centres_in_region(spheres, in.region, strip);
  if (with_segregation) {
    std::vector<double> feed;  // every powder sphere handed in, loose ones included
    for (std::uint64_t i = 0; i < in.n; ++i)
      if (!is_substrate(i)) feed.push_back(2 * in.r[i]);
    out.segregation =
        segregation(SizeSample(diameters_in_region(spheres, in.region, strip)), SizeSample(std::move(feed)));
  }
  if (depth_settings)
    out.depth = depth_profile(spheres, in.region, strip, in.substrate_z, m.mean_height, *depth_settings);

  if (solid == 0 && n_covered == 0)
    out.warnings.push_back(
        "no particle in the sampling region: height 0, coverage 0, packing fraction undefined (null)");
  else if (!(map_volume > 0))
    out.warnings.push_back("the height map encloses no volume: packing fraction undefined (null)");
  return out;
}

std::string sm::layer::metrics_json(const LayerResult &r) {
  const LayerMetrics &m = r.metrics;
  nlohmann::ordered_json metrics, units;
  const auto put = [&](const std::string &name, nlohmann::ordered_json value, const char *unit) {
    metrics[name] = std::move(value);
    units[name] = unit;
  };
  put("mean_height", number_or_null(m.mean_height), "m");
  put("rq", number_or_null(m.rq), "m");
  put("vs", number_or_null(m.vs), "m^2/s");
  put("solid_thickness", number_or_null(m.solid_thickness), "m");
  put("packing_fraction", number_or_null(m.packing_fraction), "-");
  put("packing_fraction_gap", number_or_null(m.packing_fraction_gap), "-");
  put("coverage", number_or_null(m.coverage), "-");
  put("largest_bare_patch", number_or_null(m.largest_bare_patch), "m^2");
  put("particles_in_region", m.particles_in_region, "-");
  put("cell", number_or_null(m.cell), "m");
  put("loose_spheres", m.loose_spheres, "-");
  if (const auto &g = r.segregation) {
    static constexpr const char *d[3] = {"d10", "d50", "d90"};
    for (int i = 0; i < 3; ++i) put("layer_" + std::string(d[i]), number_or_null(g->layer_d[i]), "m");
    for (int i = 0; i < 3; ++i) put("feed_" + std::string(d[i]), number_or_null(g->feed_d[i]), "m");
    for (int i = 0; i < 3; ++i) put(std::string(d[i]) + "_ratio", number_or_null(g->ratio[i]), "-");
    put("layer_d50_number", number_or_null(g->layer_d50_number), "m");
    put("feed_d50_number", number_or_null(g->feed_d50_number), "m");
    put("d50_number_ratio", number_or_null(g->d50_number_ratio), "-");
    put("fines_diameter", number_or_null(g->fines_diameter), "m");
    put("layer_fines", number_or_null(g->layer_fines), "-");
    put("feed_fines", number_or_null(g->feed_fines), "-");
  }
  nlohmann::ordered_json profiles;
  if (const auto &p = r.depth) {
    put("packing_top", number_or_null(p->packing_top), "-");
    put("packing_bulk", number_or_null(p->packing_bulk), "-");
    put("top_thickness", number_or_null(p->top_thickness), "m");
    profiles["z"] = p->z;
    profiles["packing"] = p->packing;
    profiles["units"] = {{"z", "m"}, {"packing", "-"}};
  }
  nlohmann::ordered_json doc;
  doc["metrics"] = std::move(metrics);
  doc["units"] = std::move(units);
  doc["warnings"] = r.warnings;
  if (!profiles.is_null()) doc["profiles"] = std::move(profiles);
  return doc.dump();
}
