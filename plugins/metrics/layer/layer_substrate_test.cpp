// A rough substrate in the layer metrics (sm_layer_input_v1::substrate): its spheres are ground the
// powder rests on, never layer. A hand-built scene: a 10 x 10 lattice of 100 um substrate spheres
// whose tops vary by +-20 um, and a flat monolayer of 50 um powder spheres (spacing 25 um, so it
// covers every point) lying on the highest substrate sphere. Heights are measured from the mean plane
// of the substrate's tops.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "layer_metrics.hpp"

namespace {

namespace layer = spreadmap::layer;
constexpr double um = 1e-6, side = 1000 * um;
constexpr double r_substrate = 50 * um, r_powder = 25 * um, spacing = 25 * um;
constexpr int powder_per_row = 40;  // 40 x 25 um = the 1 mm period

struct Scene {
  std::vector<double> x, y, z, r;
  std::vector<std::uint8_t> substrate;
  double mean_top = 0, powder_z = 0;
  std::size_t substrate_count = 0;

  void add(double xi, double yi, double zi, double ri, bool ground) {
    x.push_back(xi), y.push_back(yi), z.push_back(zi), r.push_back(ri), substrate.push_back(ground ? 1 : 0);
  }
  // in.substrate is null when `flags` is false; the first `skip` spheres are left out.
  sm_layer_input_v1 input(bool flags, std::size_t skip = 0) const {
    sm_layer_input_v1 in{};
    in.n = x.size() - skip;
    in.x = x.data() + skip, in.y = y.data() + skip, in.z = z.data() + skip, in.r = r.data() + skip;
    in.region[0] = 200 * um, in.region[1] = 800 * um, in.region[2] = 0, in.region[3] = side;
    in.periodic_y[0] = 0, in.periodic_y[1] = side;
    in.substrate_z = mean_top;
    in.speed = 0.1;
    in.gap = 200 * um;
    in.substrate = flags ? substrate.data() + skip : nullptr;
    return in;
  }
};

Scene rough_scene() {
  Scene s;
  double highest = 0;
  for (int i = 0; i < 10; ++i)
    for (int j = 0; j < 10; ++j) {
      const double top = 100 * um + 20 * um * std::sin(1.7 * i + 0.9 * j * j);
      s.add((i + 0.5) * 2 * r_substrate, (j + 0.5) * 2 * r_substrate, top - r_substrate, r_substrate, true);
      s.mean_top += top / 100;
      highest = std::max(highest, top);
    }
  s.substrate_count = s.x.size();
  // The monolayer's bottoms on the highest top: the sphere above that peak touches it (the lattice
  // holds every substrate centre: 100 um = 4 spacings, offset 50 um = 2), all others touch neighbours.
  s.powder_z = highest + r_powder;
  for (int i = 0; i < powder_per_row; ++i)
    for (int j = 0; j < powder_per_row; ++j) s.add(i * spacing, j * spacing, s.powder_z, r_powder, false);
  return s;
}

}  // namespace

TEST(LayerSubstrate, AMonolayerOnARoughSubstrateCoversItRestsAndIsMeasuredFromTheMeanPlane) {
  const Scene s = rough_scene();
  const auto on_substrate = layer::characterise_layer(s.input(true), 0, true, true);
  const auto &m = on_substrate.metrics;
  EXPECT_EQ(m.loose_spheres, 0u);
  EXPECT_EQ(m.coverage, 1.0);
  EXPECT_EQ(m.particles_in_region, 24u * powder_per_row);  // powder centres x = 200..775 um; no substrate
  EXPECT_NEAR(m.cell, 2 * r_powder / 5, 1e-18) << "the default cell is the powder's mean diameter / 5";
  // heights of the monolayer's surface above the mean plane: its tops where a grid point meets a
  // centre, at least r / sqrt(2) above the centres where it is farthest from one (the square's centre)
  const auto [lowest, highest] = std::minmax_element(on_substrate.height.begin(), on_substrate.height.end());
  EXPECT_NEAR(*highest, s.powder_z + r_powder - s.mean_top, 1e-15);
  EXPECT_GE(*lowest, s.powder_z + r_powder / std::sqrt(2.0) - s.mean_top - 1e-15);
  ASSERT_TRUE(on_substrate.segregation.has_value());
  EXPECT_NEAR(on_substrate.segregation->feed_d[1], 2 * r_powder, 1e-15) << "the feed is the powder alone";
  EXPECT_NEAR(on_substrate.segregation->layer_d[1], 2 * r_powder, 1e-15);
}

TEST(LayerSubstrate, TheSubstrateChangesNothingButWhatCountsAsGround) {
  const Scene s = rough_scene();
  const auto with = layer::characterise_layer(s.input(true), 0, true);
  const auto powder_alone = layer::characterise_layer(s.input(false, s.substrate_count), 0, false);
  EXPECT_EQ(with.metrics.mean_height, powder_alone.metrics.mean_height);
  EXPECT_EQ(with.metrics.rq, powder_alone.metrics.rq);
  EXPECT_EQ(with.metrics.solid_thickness, powder_alone.metrics.solid_thickness);
  EXPECT_EQ(with.metrics.packing_fraction, powder_alone.metrics.packing_fraction);
  EXPECT_EQ(with.metrics.packing_fraction_gap, powder_alone.metrics.packing_fraction_gap);
  EXPECT_EQ(with.metrics.coverage, powder_alone.metrics.coverage);
  EXPECT_EQ(with.metrics.particles_in_region, powder_alone.metrics.particles_in_region);
  EXPECT_EQ(with.height, powder_alone.height);
}

TEST(LayerSubstrate, WithoutTheFlagsTheSubstrateWouldBeLayerAndThePowderOnItsPeaksLoose) {
  const Scene s = rough_scene();
  // unflagged, the substrate's spheres (bottoms below the mean plane) rest and count as layer:
  // 6 x 10 centres in the region besides the powder's
  const auto unflagged = layer::characterise_layer(s.input(false), 0, true);
  EXPECT_EQ(unflagged.metrics.particles_in_region, 24u * powder_per_row + 60u);
  // the powder alone over a flat plane at the mean: every sphere lies above it on the peaks, so
  // every sphere would be loose (why the host hands the substrate's spheres in rather than a plane)
  const auto plane_only = layer::characterise_layer(s.input(false, s.substrate_count), 0, true);
  EXPECT_EQ(plane_only.metrics.loose_spheres, std::uint64_t(powder_per_row * powder_per_row));
}

TEST(LayerSubstrate, APowderSphereInFlightIsLooseTheSubstrateNever) {
  Scene s = rough_scene();
  s.add(500 * um, 500 * um, s.powder_z + 1e-3, r_powder, false);
  const auto m = layer::characterise_layer(s.input(true), 0, true).metrics;
  EXPECT_EQ(m.loose_spheres, 1u);
  EXPECT_EQ(m.coverage, 1.0);
}
