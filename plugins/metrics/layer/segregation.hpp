// Segregation: the size distribution of the spread layer against the feed it was spread from.
//
// The layer is the spheres whose centres lie in the sampling region (those counted by
// particles_in_region); the feed is every sphere of the state handed to the plugin (the whole scene:
// the heap's particles wherever spreading left them, spheres in flight included, none lost unless
// the engine removed them for leaving the domain). Percentiles are by volume (= by mass at one
// density) unless named _number, with SizeSample's convention (no interpolation: the smallest
// diameter whose cumulative share reaches p). Fines are the spheres strictly smaller than the feed's
// D10 by volume; their share is by volume.
//
// Metrics (SI): layer_d10, layer_d50, layer_d90, feed_d10, feed_d50, feed_d90 [m]; d10_ratio,
// d50_ratio, d90_ratio = layer / feed [-]; layer_d50_number, feed_d50_number [m] and
// d50_number_ratio [-]; fines_diameter, the feed's D10 by volume [m]; layer_fines, feed_fines, the
// volume share of fines [-]. A ratio above 1 means a coarser layer than the feed. Undefined (NaN,
// null in JSON) when the layer holds no sphere.
#pragma once
#include <spreadmap/size_sample.hpp>

#include <vector>

namespace spreadmap::layer {

struct SegregationMetrics {
  double layer_d[3], feed_d[3], ratio[3];  // D10, D50, D90 by volume [m], and layer / feed [-]
  double layer_d50_number, feed_d50_number, d50_number_ratio;
  double fines_diameter, layer_fines, feed_fines;
};

SegregationMetrics segregation(const SizeSample &layer, const SizeSample &feed);

}  // namespace spreadmap::layer
