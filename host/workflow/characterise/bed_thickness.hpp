// How thick the powder of each layer of a multi-layer case is (scene.layers), from consecutive layers.
//
// Heights are in the plate's frame (z = 0 the plate of layer 1, where layer_feed.hpp keeps the bed).
// For layer k (1-based):
//   effective_thickness_k = e_k - H_(k-1)   the powder thickness the spreader meets: its lower edge
//                                           e_k = gap + (k - 1) x thickness above the plate, less the
//                                           mean height H of the bed left by layer k - 1 (H_0 = 0: the
//                                           bare plate, so layer 1's is the gap)
//   deposited_thickness_k = S_k - S_(k-1)   the solid the pass added: S = solid volume in the sampling
//                                           region / its area (solid_thickness), S_0 = 0
//   layer_relative_density_k = deposited_thickness_k / (e_k - e_(k-1))   with e_0 = 0: the solid the
//                                           pass added over the platform's drop (layer 1: over its
//                                           gap), as multi-layer experiments measure a layer's density
// Thicknesses in metres, the density a fraction; NaN where a value they need is undefined.
#pragma once
#include <vector>

namespace spreadmap {

struct LayerBed {
  double spreader_edge = 0;    // e_k: the spreader's lower edge above the plate while spreading layer k [m]
  double mean_height = 0;      // H_k: mean height of the bed after layer k [m]
  double solid_thickness = 0;  // S_k [m]
};

struct LayerThickness {
  double effective = 0, deposited = 0;  // [m]
  double relative_density = 0;          // [-]
};

// One entry per layer, in layer order (layers[0] is layer 1).
std::vector<LayerThickness> layer_thicknesses(const std::vector<LayerBed> &layers);

}  // namespace spreadmap
