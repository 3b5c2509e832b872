// Characterising one spread layer through a metrics plugin: the particles, the sampling region and
// what the case knows (spreader speed and gap, periodic strip) in; metrics, units and the height
// map out. Shared by the characterise stage and `spreadmap characterise`.
#pragma once
#include <cmath>
#include <filesystem>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include <spreadmap/geometry.hpp>

#include "core/registry.hpp"
#include "engine/particle_set.hpp"
#include "workflow/spreading/scene_model.hpp"

namespace spreadmap {

struct Region {
  double x0 = 0, x1 = 0, y0 = 0, y1 = 0;  // [m]
};

struct LayerRequest {
  std::string plugin;  // metrics plugin; empty: the first that declares the metric contract
  nlohmann::json params = nlohmann::json::object();  // validated SI values of the plugin's schema
  Region region;
  double substrate_z = 0;
  std::optional<std::pair<double, double>> periodic_y;      // y_lo, y_hi of a periodic strip
  double speed = std::numeric_limits<double>::quiet_NaN();  // U for V_s [m/s]
  double gap = std::numeric_limits<double>::quiet_NaN();    // spreader gap [m]
};

struct LayerResult {
  nlohmann::json metrics;  // name -> SI value or null
  nlohmann::json units;    // name -> SI unit
  std::vector<std::string> warnings;
  nlohmann::json profiles;  // the plugin's "profiles" (e.g. packing against depth); null when it has none
  std::uint32_t nx = 0, ny = 0;
  double x0 = 0, y0 = 0, cell = 0;
  std::vector<double> height;  // row-major iy * nx + ix [m] above the substrate
};

// The fixed spheres of `p` (its `fixed` column: a rough substrate's) are handed to the plugin as
// substrate, ground rather than layer.
LayerResult characterise_layer(PluginRegistry &registry, const LayerRequest &request, const engine::ParticleSet &p);

// A particle state: spreadmap's .vtp, or a CSV with x, y, z, radius columns [m].
engine::ParticleSet read_particle_file(const std::filesystem::path &file);

// "14mm:24mm,0:2.5mm" -> region; bare numbers are metres. Throws InputError naming `what`.
Region parse_region(const std::string &text, const std::string &what);

// The sampling region of a scene when the workflow sets none: the study's 50 mm x 50 mm square
// centred on the substrate for full-width scenes; for periodic strips the whole width over the
// middle 40 % of the spreader's travel.
Region default_region(const Scene &scene, const sm_spreader_description_v2 &spreader);

// What the layer's metrics take from the spreader that spread it: its speed U (V_s = mean height x
// U) and its gap.
void take_spreader(LayerRequest &request, const sm_spreader_description_v2 &spreader);

// The metric columns of metrics.csv, in this order (extra metrics of other plugins follow).
const std::vector<std::string> &standard_metric_order();

}  // namespace spreadmap
