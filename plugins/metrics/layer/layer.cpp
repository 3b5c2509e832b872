// metrics/layer: characterises a spread powder layer from its spheres.
//
// Samples the height map h(x, y) (top of the highest sphere above the substrate) on a grid of square
// cells over the host's sampling region and reports mean height, R_q (std. deviation of h), V_s (mean
// height x U, the study's spread rate per unit roller width), solid thickness with spheres clipped
// exactly by the region, packing fractions, coverage and the largest bare patch, all in SI with their
// units. Spheres resting on nothing (in flight) are left out by default (resting.hpp); the spheres
// the host flags as substrate (a rough substrate's, from 1.3) are ground, never layer. With
// `segregation: true` it also compares the layer's size distribution with the feed's (segregation.hpp);
// with `depth_profile: true` it reports packing against depth (depth_profile.hpp).
// The algorithm lives in layer_metrics / heightmap / segregation (plain C++, tested directly); this
// file is only the class the SDK wraps (spreadmap/metric.hpp). The plugin writes no file: the host asks for the last map through heightmap().
#include <spreadmap/metric.hpp>
#include <spreadmap/plugin.hpp>

#include <cstdio>
#include <exception>
#include <optional>
#include <string>

#include "layer_metrics.hpp"

namespace sm = spreadmap;

namespace {

class Layer {
 public:
  static constexpr sm_param_v1 params[] = {
      sm::number("grid", "m", 0.0, 1.0, 0.0,
                 "height-map cell size (square cells, sampled at their centres); 0 = mean sphere diameter / 5"),
      sm::boolean("exclude_loose", true,
                  "leave out spheres resting on nothing (in flight when the state was taken); false: every sphere"),
      sm::boolean("segregation", false,
                  "also the layer's sizes against the feed (every sphere): layer_/feed_ d10, d50, d90 by volume [m], "
                  "their d*_ratio = layer/feed [-], d50 by number (*_number), fines_diameter = feed D10 [m], "
                  "layer_fines/feed_fines = volume share below it [-]"),
      sm::boolean("depth_profile", false,
                  "also packing against depth: solid fraction in horizontal slices from the substrate up (the "
                  "profile in metrics.json), packing_top = the top_thickness below the mean surface, packing_bulk "
                  "= the bed below that [-]"),
      sm::number("depth_slice", "m", 1e-9, 1.0, 50e-6, "slice thickness of the depth profile"),
      sm::number("top_thickness", "m", 0.0, 1.0, 0.0,
                 "thickness below the mean surface that packing_top covers; 0 = two mean sphere diameters "
                 "(a multi-layer bed: give the layer thickness)"),
  };
  static constexpr sm_metric_v1 gives[] = {
      {"mean_height", "m", "mean height of the height map above the substrate"},
      {"rq", "m", "R_q: standard deviation of the height map"},
      {"vs", "m^2/s", "V_s: volume spread per unit spreader width and time, mean height x U"},
      {"solid_thickness", "m", "solid volume in the region per its area (spheres clipped by the region)"},
      {"packing_fraction", "-", "solid volume per volume under the height map"},
      {"packing_fraction_gap", "-", "solid volume per region area x spreader gap"},
      {"coverage", "-", "share of the region's cells with powder"},
      {"largest_bare_patch", "m^2", "area of the largest connected patch without powder"},
      {"particles_in_region", "-", "spheres whose centre lies in the region"},
      {"cell", "m", "height-map cell size"},
      {"loose_spheres", "-", "spheres left out as resting on nothing"},
  };
  static Layer bind(const sm::Values &v) {
    Layer layer;
    layer.cell_ = v["grid"];
    layer.exclude_loose_ = v.boolean("exclude_loose");
    layer.segregation_ = v.has("segregation") && v.boolean("segregation");  // absent (callers before 1.1): off
    if (v.has("depth_profile") && v.boolean("depth_profile")) {             // absent (callers before 1.2): off
      layer.depth_.emplace();
      if (v.has("depth_slice")) layer.depth_->slice = v["depth_slice"];
      if (v.has("top_thickness")) layer.depth_->top_thickness = v["top_thickness"];
    }
    if (layer.cell_ < 0) throw sm::ParamError("grid = " + std::to_string(layer.cell_) + " m must be >= 0 (0 = d/5)");
    return layer;
  }

  const char *evaluate(const sm_layer_input_v1 &in) {
    last_ = sm::layer::characterise_layer(in, cell_, exclude_loose_, segregation_, depth_ ? &*depth_ : nullptr);
    json_ = sm::layer::metrics_json(last_);
    return json_.c_str();
  }
  sm::HeightMapView heightmap() const {
    if (last_.height.empty()) return {};
    return {uint32_t(last_.grid.nx), uint32_t(last_.grid.ny), last_.grid.x0, last_.grid.y0, last_.grid.cell,
            last_.height.data()};
  }

 private:
  double cell_ = 0;
  bool exclude_loose_ = true;
  bool segregation_ = false;
  std::optional<sm::layer::DepthSettings> depth_;
  sm::layer::LayerResult last_;
  std::string json_;  // owned here: valid until the next evaluate() or destroy()
};

}  // namespace

SPREADMAP_METRICS_PLUGIN(Layer, "layer", "1.4.0",
                         "height map, R_q, V_s, solid thickness, packing, coverage and bare patches of a spread layer; "
                         "optionally its size distribution against the feed and its packing against depth")
