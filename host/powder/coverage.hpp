// Will the heap last? A spread layer holds about packing * thickness of solid per unit area, so a
// heap of solid volume V covers a strip of width W over V / (packing * thickness * W).
// Defaults are conservative on purpose: the brief's packing 0.6 with thickness = gap. In the peer
// LIGGGHTS runs (gap 0.5 mm = 2 d, paper-notes) the layer held 0.23-0.27 mm of solid per unit area,
// i.e. 0.47-0.54 of the gap, less than the 0.6 assumed here, so the estimate errs on the short side.
#pragma once

namespace spreadmap::powder {

struct LayerCoverage {
  double coverable_length;  // length of layer the heap can fill [m]
  double required_length;   // what was asked [m]
  bool sufficient;          // coverable_length >= required_length
};

// solid_volume [m^3]: the heap's powder volume; layer_thickness [m] (~ the gap); width [m] of the
// strip (the periodic width, or the spreader length); required_length [m]: from where spreading
// starts to the far end of the sampled region. packing: solid fraction of the spread layer.
// Throws PowderError for non-positive thickness, width or packing.
LayerCoverage sampled_length_check(double solid_volume, double layer_thickness, double width, double required_length,
                                   double packing = 0.6);

}  // namespace spreadmap::powder
