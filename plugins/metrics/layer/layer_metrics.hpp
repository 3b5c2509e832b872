// Layer characterisation: the height map of a spread layer and the metrics derived from it.
//
// Metrics (SI): mean_height [m]; rq, the population standard deviation of h [m]; vs = mean height x U
// [m^2/s]; solid_thickness, sphere volume inside the region (spheres clipped exactly by the region's
// vertical planes) over the region's area [m]; packing_fraction, solid volume over the volume between
// the substrate and the height map [-]; packing_fraction_gap, solid volume over region area x gap [-];
// coverage, share of covered grid points [-]; largest_bare_patch, area of the largest 4-connected set
// of uncovered grid points [m^2] (not wrapped across a periodic strip); particles_in_region, centres in
// [x0, x1) x [y0, y1) [-]; cell, the grid's cell [m]; loose_spheres, spheres left out because they
// rest on nothing (exclude_loose) [-]. An undefined value is NaN here and null in JSON,
// never a silent number: vs without a speed, packing_fraction when the map's volume is 0,
// packing_fraction_gap without a gap. With `segregation`, also the layer's size distribution against
// the feed (segregation.hpp). With a DepthSettings, also packing against depth (depth_profile.hpp):
// packing_top, packing_bulk [-], top_thickness [m], and the profile under "profiles".
#pragma once
#include <spreadmap/metric.hpp>

#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "depth_profile.hpp"
#include "heightmap.hpp"
#include "segregation.hpp"

namespace spreadmap::layer {

inline constexpr double undefined = std::numeric_limits<double>::quiet_NaN();  // a metric with no value

struct LayerMetrics {
  double mean_height = 0, rq = 0, vs = 0, solid_thickness = 0, packing_fraction = 0, packing_fraction_gap = 0;
  double coverage = 0, largest_bare_patch = 0, cell = 0;
  std::uint64_t particles_in_region = 0;
  std::uint64_t loose_spheres = 0;  // left out with exclude_loose (anywhere, not only in the region)
};

struct LayerResult {
  Grid grid;
  std::vector<double> height;         // row-major, above the substrate [m]
  std::vector<std::uint8_t> covered;  // 1 where a sphere covers the grid point
  LayerMetrics metrics;
  std::optional<SegregationMetrics> segregation;  // when asked for
  std::optional<DepthProfile> depth;              // when asked for
  std::vector<std::string> warnings;              // sentences for the user; the host logs them
};

// The whole characterisation. `cell` is the plugin's `grid` parameter: 0 means mean diameter / 5.
// The spheres `in.substrate` flags (a rough substrate's) are ground: never part of the layer, its
// heights, coverage, solid, packing or sizes. exclude_loose: only the powder spheres resting on the
// ground (the plane at substrate_z or a substrate sphere, directly or through touching spheres,
// resting.hpp) make the layer; loose_spheres counts the other powder spheres. with_segregation: also
// the layer's size distribution against the feed, every powder sphere of `in`. depth: also packing
// against depth, of the spheres that make the layer. Throws std::invalid_argument for
// unusable input (empty region, non-finite sphere data).
LayerResult characterise_layer(const sm_layer_input_v1 &in, double cell, bool exclude_loose = false,
                               bool with_segregation = false, const DepthSettings *depth = nullptr);

// {"metrics": {...}, "units": {...}, "warnings": [...]}; NaN metrics are written as null. With a depth
// profile also "profiles": {"z": [...], "packing": [...], "units": {"z": "m", "packing": "-"}}.
std::string metrics_json(const LayerResult &result);

// Pieces, usable on their own (tests, other tools).
double mean_diameter(const SphereArrays &spheres);  // 0 when there are no spheres
// Sphere volume inside the prism region[4] = x0, x1, y0, y1, periodic images included [m^3].
double solid_volume_in_region(const SphereArrays &spheres, const double region[4], const PeriodicStrip &strip);
// Centres (periodic images included) in [x0, x1) x [y0, y1).
std::uint64_t centres_in_region(const SphereArrays &spheres, const double region[4], const PeriodicStrip &strip);
// The diameters of those centres, one per centre counted by centres_in_region [m].
std::vector<double> diameters_in_region(const SphereArrays &spheres, const double region[4],
                                        const PeriodicStrip &strip);
// Number of grid points in the largest 4-connected set of uncovered points.
std::size_t largest_bare_patch_points(const std::vector<std::uint8_t> &covered, std::uint32_t nx, std::uint32_t ny);

}  // namespace spreadmap::layer
