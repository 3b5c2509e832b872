#include "segregation.hpp"

namespace sm = spreadmap;

sm::layer::SegregationMetrics sm::layer::segregation(const SizeSample &layer, const SizeSample &feed) {
  constexpr double shares[3] = {0.1, 0.5, 0.9};
  SegregationMetrics m{};
  for (int i = 0; i < 3; ++i) {
    m.layer_d[i] = layer.percentile(shares[i], SizeBasis::volume);
    m.feed_d[i] = feed.percentile(shares[i], SizeBasis::volume);
    m.ratio[i] = m.layer_d[i] / m.feed_d[i];
  }
  m.layer_d50_number = layer.percentile(0.5, SizeBasis::number);
  m.feed_d50_number = feed.percentile(0.5, SizeBasis::number);
  m.d50_number_ratio = m.layer_d50_number / m.feed_d50_number;
  m.fines_diameter = m.feed_d[0];
  m.layer_fines = layer.share_below(m.fines_diameter, SizeBasis::volume);
  m.feed_fines = feed.share_below(m.fines_diameter, SizeBasis::volume);
  return m;
}
