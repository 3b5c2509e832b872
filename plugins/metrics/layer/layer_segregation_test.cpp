// Segregation metrics of metrics/layer against hand-computed values: the SDK's SizeSample
// percentiles (by volume and by number, no interpolation: the smallest diameter whose cumulative
// share reaches p), a layer holding exactly the feed, and a layer holding only the feed's spheres
// larger than its D50.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include <spreadmap/size_sample.hpp>

#include "layer_metrics.hpp"

namespace sm = spreadmap;
using sm::SizeBasis;
using sm::SizeSample;

namespace {

constexpr double um = 1e-6;

// Spheres of the given diameters resting on the substrate (z = r) in a row along x from x0, 1 um apart.
struct Row {
  std::vector<double> x, y, z, r;
  void add(const std::vector<double> &diameters, double x0) {
    double at = x0;
    for (double d : diameters) {
      x.push_back(at + d / 2), y.push_back(50 * um), z.push_back(d / 2), r.push_back(d / 2);
      at += d + 1 * um;
    }
  }
  sm_layer_input_v1 input(double x0, double x1) const {
    sm_layer_input_v1 in{};
    in.n = x.size();
    in.x = x.data(), in.y = y.data(), in.z = z.data(), in.r = r.data();
    in.region[0] = x0, in.region[1] = x1, in.region[2] = 0, in.region[3] = 100 * um;
    in.speed = in.gap = std::nan("");
    return in;
  }
};

sm::layer::SegregationMetrics characterise(const Row &row, double x0, double x1) {
  const auto result = sm::layer::characterise_layer(row.input(x0, x1), 10 * um, false, true);
  EXPECT_TRUE(result.segregation.has_value());
  return *result.segregation;
}

}  // namespace

// 20 spheres of 10 um, 5 of 20 um, 2 of 30 um, 1 of 40 um. Volumes in units of (10 um)^3: 20, 40,
// 54, 64 (total 178), cumulative shares 20/178 = 0.112, 60/178 = 0.337, 114/178 = 0.640, 1: D10 =
// 10 um, D50 = 30 um, D90 = 40 um by volume. By number (28): 20/28 = 0.714, 25/28 = 0.893, 27/28 =
// 0.964, 1: D10 = D50 = 10 um, D90 = 30 um.
TEST(LayerSegregation, PercentilesOfAKnownSetByVolumeAndByNumber) {
  std::vector<double> d(20, 10 * um);
  d.insert(d.end(), 5, 20 * um);
  d.insert(d.end(), {30 * um, 40 * um, 30 * um});  // order does not matter
  const SizeSample s(d);
  EXPECT_EQ(s.size(), 28u);
  EXPECT_EQ(s.percentile(0.1, SizeBasis::volume), 10 * um);
  EXPECT_EQ(s.percentile(0.5, SizeBasis::volume), 30 * um);
  EXPECT_EQ(s.percentile(0.9, SizeBasis::volume), 40 * um);
  EXPECT_EQ(s.percentile(0.1, SizeBasis::number), 10 * um);
  EXPECT_EQ(s.percentile(0.5, SizeBasis::number), 10 * um);
  EXPECT_EQ(s.percentile(0.9, SizeBasis::number), 30 * um);
  // Strictly below 20 um: the twenty 10 um spheres.
  EXPECT_DOUBLE_EQ(s.share_below(20 * um, SizeBasis::volume), 20.0 / 178.0);
  EXPECT_DOUBLE_EQ(s.share_below(20 * um, SizeBasis::number), 20.0 / 28.0);
  EXPECT_EQ(s.share_below(10 * um, SizeBasis::volume), 0.0);
  EXPECT_EQ(s.share_below(41 * um, SizeBasis::volume), 1.0);
}

// A share met exactly takes that diameter, not a mean with the next one: two spheres by number,
// cumulative shares 0.5 and 1, so D50 is the smaller.
TEST(LayerSegregation, AShareMetExactlyTakesTheLowerDiameter) {
  const SizeSample s({20 * um, 10 * um});
  EXPECT_EQ(s.percentile(0.5, SizeBasis::number), 10 * um);
  EXPECT_EQ(s.percentile(0.51, SizeBasis::number), 20 * um);
  EXPECT_EQ(s.percentile(1.0, SizeBasis::number), 20 * um);
  EXPECT_TRUE(std::isnan(s.percentile(0.0, SizeBasis::number)));
  EXPECT_TRUE(std::isnan(SizeSample({}).percentile(0.5, SizeBasis::volume)));
  EXPECT_TRUE(std::isnan(SizeSample({}).share_below(1.0, SizeBasis::volume)));
}

// Every sphere inside the region: the layer is the feed, every ratio is 1 and the fines shares are equal.
TEST(LayerSegregation, ALayerHoldingTheFeedHasRatiosOfOne) {
  std::vector<double> d;
  for (int k = 0; k < 40; ++k) d.push_back((15 + 30 * std::fmod(0.618 * k, 1.0)) * um);  // 15..45 um
  Row row;
  row.add(d, 10 * um);
  const auto m = characterise(row, 0, 2e-3);
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(m.ratio[i], 1.0) << i;
    EXPECT_EQ(m.layer_d[i], m.feed_d[i]) << i;
  }
  EXPECT_EQ(m.d50_number_ratio, 1.0);
  EXPECT_EQ(m.layer_fines, m.feed_fines);
  EXPECT_GT(m.feed_fines, 0.0);
  EXPECT_LT(m.feed_fines, 0.1);  // strictly below D10: less than a tenth
}

// Feed: diameters k x 5 um, k = 1..20. Volumes k^3, cumulative (k (k + 1) / 2)^2 of 210^2 = 44100.
// Feed D10: first k with (k(k+1)/2)^2 >= 4410 is 12 (78^2 = 6084; k = 11 gives 66^2 = 4356); D50
// (>= 22050): 17 (153^2 = 23409; 136^2 = 18496 below); D90 (>= 39690): 20 (190^2 = 36100 below).
// The layer holds only k = 18, 19, 20 (larger than the feed's D50), volumes 5832, 6859, 8000 of
// 20691: D10 = 18, D50 = 19 (12691 >= 10345.5), D90 = 20. Ratios 18/12, 19/17, 1. By number the
// feed's D50 is k = 10, the layer's 19. Fines (below 60 um): none in the layer, 4356/44100 of the feed.
TEST(LayerSegregation, ALayerOfTheSpheresAboveTheFeedMedian) {
  std::vector<double> small, large;
  for (int k = 1; k <= 17; ++k) small.push_back(k * 5 * um);
  for (int k = 18; k <= 20; ++k) large.push_back(k * 5 * um);
  Row row;
  row.add(large, 0);
  row.add(small, 1e-3);  // outside the region [0, 0.5 mm)
  const auto m = characterise(row, 0, 0.5e-3);
  EXPECT_DOUBLE_EQ(m.feed_d[0], 60 * um);
  EXPECT_DOUBLE_EQ(m.feed_d[1], 85 * um);
  EXPECT_DOUBLE_EQ(m.feed_d[2], 100 * um);
  EXPECT_DOUBLE_EQ(m.layer_d[1], 95 * um);
  EXPECT_DOUBLE_EQ(m.ratio[0], 18.0 / 12.0);
  EXPECT_DOUBLE_EQ(m.ratio[1], 19.0 / 17.0);
  EXPECT_DOUBLE_EQ(m.ratio[2], 1.0);
  EXPECT_DOUBLE_EQ(m.feed_d50_number, 50 * um);
  EXPECT_DOUBLE_EQ(m.d50_number_ratio, 19.0 / 10.0);
  EXPECT_DOUBLE_EQ(m.fines_diameter, 60 * um);
  EXPECT_EQ(m.layer_fines, 0.0);
  EXPECT_DOUBLE_EQ(m.feed_fines, 4356.0 / 44100.0);
}

// The layer is what particles_in_region counts; an empty region leaves every layer value undefined.
TEST(LayerSegregation, AnEmptyLayerIsUndefinedNotZero) {
  Row row;
  row.add({30 * um, 40 * um}, 1e-3);
  const auto result = sm::layer::characterise_layer(row.input(0, 0.5e-3), 10 * um, false, true);
  EXPECT_EQ(result.metrics.particles_in_region, 0u);
  const auto &m = *result.segregation;
  EXPECT_TRUE(std::isnan(m.layer_d[1]));
  EXPECT_TRUE(std::isnan(m.ratio[1]));
  EXPECT_TRUE(std::isnan(m.layer_fines));
  EXPECT_EQ(m.feed_d[1], 40 * um);
  const std::string json = sm::layer::metrics_json(result);
  EXPECT_NE(json.find("\"d50_ratio\":null"), std::string::npos) << json;
  EXPECT_EQ(sm::layer::metrics_json(sm::layer::characterise_layer(row.input(0, 0.5e-3), 10 * um)).find("d50_ratio"),
            std::string::npos);  // not asked for: not reported
}
