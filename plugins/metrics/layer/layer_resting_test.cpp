// Which spheres make the layer (resting.hpp): resting on the substrate directly or through touching
// spheres, across a periodic seam too; spheres in flight, alone or as a touching pair, do not. And
// the layer metrics without them equal those of the layer alone, bit for bit.
#include <gtest/gtest.h>

#include <vector>

#include "layer_metrics.hpp"
#include "resting.hpp"

namespace {

namespace layer = spreadmap::layer;
constexpr double r = 125e-6;

struct Spheres {
  std::vector<double> x, y, z, rad;
  void add(double xi, double yi, double zi) { x.push_back(xi), y.push_back(yi), z.push_back(zi), rad.push_back(r); }
  layer::SphereArrays view() const { return {x.size(), x.data(), y.data(), z.data(), rad.data()}; }
  sm_layer_input_v1 input(double width) const {
    sm_layer_input_v1 in{};
    in.n = x.size(), in.x = x.data(), in.y = y.data(), in.z = z.data(), in.r = rad.data();
    in.region[0] = 0, in.region[1] = 3e-3, in.region[2] = 0, in.region[3] = width;
    in.periodic_y[0] = 0, in.periodic_y[1] = width;
    in.speed = 0.1;
    in.gap = 0.5e-3;
    return in;
  }
};

}  // namespace

TEST(LayerResting, StacksAndChainsRestInFlightDoesNot) {
  Spheres s;
  s.add(1e-3, 0.5e-3, r);                 // 0: on the substrate
  s.add(1e-3, 0.5e-3, 3 * r - 1e-9);      // 1: on 0 (touching, overlap 1 nm)
  s.add(1e-3 + 2 * r - 1e-9, 0.5e-3, r);  // 2: beside 0, on the substrate
  s.add(2e-3, 0.5e-3, 1.2e-3);            // 3: alone in flight
  s.add(2.5e-3, 0.5e-3, 1.5e-3);          // 4, 5: a touching pair in flight
  s.add(2.5e-3, 0.5e-3, 1.5e-3 + 2 * r);
  s.add(1e-3, 0.5e-3, 5 * r + 0.5 * r);  // 6: half a radius above 1: not touching
  const auto resting = layer::resting_spheres(s.view(), 0.0, {0, 1e-3});
  EXPECT_EQ(resting, (std::vector<std::uint8_t>{1, 1, 1, 0, 0, 0, 0}));
}

TEST(LayerResting, TouchingAcrossThePeriodicSeamCounts) {
  const double width = 1e-3;
  Spheres s;
  s.add(1e-3, 0.05 * r, r);                     // on the substrate at the lower edge
  s.add(1e-3, width - 0.05 * r, 3 * r - 1e-9);  // on top of it through the seam (dy = 0.1 r)
  const auto periodic = layer::resting_spheres(s.view(), 0.0, {0, width});
  // minimum-image separation sqrt((0.1 r)^2 + (2 r - 1e-9)^2) = 1.0012 x 2 r: within the 1 % tolerance
  EXPECT_EQ(periodic, (std::vector<std::uint8_t>{1, 1}));
  const auto open = layer::resting_spheres(s.view(), 0.0, {0, 0});
  EXPECT_EQ(open, (std::vector<std::uint8_t>{1, 0})) << "without the strip the two are a width apart";
}

TEST(LayerResting, LoosePairLeavesTheLayerMetricsOfTheLayerAlone) {
  // A square monolayer on the substrate, then the same with two spheres in flight above it.
  const double width = 1e-3;
  Spheres layer_only;
  for (int i = 0; i < 12; ++i)
    for (int j = 0; j < 4; ++j) layer_only.add((i + 0.5) * 2 * r, (j + 0.5) * 2 * r, r);
  Spheres with_flight = layer_only;
  with_flight.add(1.2e-3, 0.4e-3, 1.3e-3);
  with_flight.add(1.2e-3, 0.4e-3, 1.3e-3 + 2 * r);
  const auto alone = layer::characterise_layer(layer_only.input(width), 25e-6, true);
  const auto kept = layer::characterise_layer(with_flight.input(width), 25e-6, true);
  const auto all = layer::characterise_layer(with_flight.input(width), 25e-6, false);
  EXPECT_EQ(kept.metrics.loose_spheres, 2u);
  EXPECT_EQ(alone.metrics.loose_spheres, 0u);
  EXPECT_EQ(kept.metrics.rq, alone.metrics.rq);
  EXPECT_EQ(kept.metrics.mean_height, alone.metrics.mean_height);
  EXPECT_EQ(kept.metrics.solid_thickness, alone.metrics.solid_thickness);
  EXPECT_GT(all.metrics.rq, 1.5 * alone.metrics.rq) << "two spheres in flight should dominate R_q when counted";
  ASSERT_EQ(kept.warnings.size(), 1u);
  EXPECT_NE(kept.warnings[0].find("2 sphere(s) rest on nothing"), std::string::npos) << kept.warnings[0];
}
