#include "workflow/characterise/bed_thickness.hpp"

namespace spreadmap {

std::vector<LayerThickness> layer_thicknesses(const std::vector<LayerBed> &layers) {
  std::vector<LayerThickness> out;
  double below_height = 0, below_solid = 0, below_edge = 0;  // the bare plate under layer 1
  for (const LayerBed &b : layers) {
    const double deposited = b.solid_thickness - below_solid;
    out.push_back({b.spreader_edge - below_height, deposited, deposited / (b.spreader_edge - below_edge)});
    below_height = b.mean_height;
    below_solid = b.solid_thickness;
    below_edge = b.spreader_edge;
  }
  return out;
}

}  // namespace spreadmap
