// Effective and deposited thickness of the layers of a multi-layer bed (bed_thickness.hpp), for beds
// whose heights and solid are known.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "workflow/characterise/bed_thickness.hpp"

namespace sm = spreadmap;

namespace {
constexpr double um = 1e-6;
}

// Gap 100 um, layer thickness 50 um: the spreader's edge at 100, 150, 200 um above the plate. Beds
// of mean height 80, 140, 195 um holding 45, 80, 112 um of solid: the spreader meets 100, 150 - 80 =
// 70 and 200 - 140 = 60 um of room, and the passes add 45, 35 and 32 um of solid.
TEST(LayerThickness, ThreeLayersOfAKnownBed) {
  const auto t = sm::layer_thicknesses(
      {{100 * um, 80 * um, 45 * um}, {150 * um, 140 * um, 80 * um}, {200 * um, 195 * um, 112 * um}});
  ASSERT_EQ(t.size(), 3u);
  EXPECT_NEAR(t[0].effective, 100 * um, 1e-15);
  EXPECT_NEAR(t[1].effective, 70 * um, 1e-15);
  EXPECT_NEAR(t[2].effective, 60 * um, 1e-15);
  EXPECT_NEAR(t[0].deposited, 45 * um, 1e-15);
  EXPECT_NEAR(t[1].deposited, 35 * um, 1e-15);
  EXPECT_NEAR(t[2].deposited, 32 * um, 1e-15);
  // the solid added over the platform's drop (50 um), layer 1 over its gap (100 um)
  EXPECT_NEAR(t[0].relative_density, 0.45, 1e-12);
  EXPECT_NEAR(t[1].relative_density, 0.70, 1e-12);
  EXPECT_NEAR(t[2].relative_density, 0.64, 1e-12);
}

// Simple cubic rows of 50 um spheres, one row per pass with the spreader 50 um above the last row's
// top: each pass meets 50 um of room (the bed's mean height is the row tops, flat-topped in the mean
// by construction here) and adds pi/6 x 50 um of solid.
TEST(LayerThickness, OneLatticeRowPerPass) {
  const double d = 50 * um, row_solid = std::numbers::pi / 6 * d;
  std::vector<sm::LayerBed> beds;
  for (int k = 1; k <= 4; ++k) beds.push_back({k * d, k * d, k * row_solid});
  const auto t = sm::layer_thicknesses(beds);
  for (const auto &layer : t) {
    EXPECT_NEAR(layer.effective, d, 1e-15);
    EXPECT_NEAR(layer.deposited, row_solid, 1e-15);
    EXPECT_NEAR(layer.relative_density, std::numbers::pi / 6, 1e-12) << "a simple cubic lattice's packing";
  }
}

// An undefined mean height (no powder in the region) leaves the next layer's effective thickness
// undefined, not a number made up.
TEST(LayerThickness, UndefinedHeightGivesUndefinedThickness) {
  const auto t = sm::layer_thicknesses({{100 * um, std::nan(""), 0}, {150 * um, 140 * um, 80 * um}});
  EXPECT_NEAR(t[0].effective, 100 * um, 1e-15);
  EXPECT_TRUE(std::isnan(t[1].effective));
  EXPECT_NEAR(t[1].deposited, 80 * um, 1e-15);
}
