// Height map and layer metrics on small scenes whose answers are known exactly: grid counting, a random
// layer against brute force (every sphere at every grid point), periodic images, the empty region,
// 4-connected bare patches.
#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <numbers>
#include <random>
#include <vector>

#include "layer_metrics.hpp"

namespace {

namespace layer = spreadmap::layer;
constexpr double pi = std::numbers::pi;
constexpr double nan = std::numeric_limits<double>::quiet_NaN();

struct Spheres {
  std::vector<double> x, y, z, r;
  void add(double xi, double yi, double zi, double ri) {
    x.push_back(xi);
    y.push_back(yi);
    z.push_back(zi);
    r.push_back(ri);
  }
  layer::SphereArrays view() const { return {x.size(), x.data(), y.data(), z.data(), r.data()}; }
  sm_layer_input_v1 input(double x0, double x1, double y0, double y1) const {
    sm_layer_input_v1 in{};
    in.n = x.size();
    in.x = x.data();
    in.y = y.data();
    in.z = z.data();
    in.r = r.data();
    in.region[0] = x0;
    in.region[1] = x1;
    in.region[2] = y0;
    in.region[3] = y1;
    in.speed = nan;
    in.gap = nan;
    return in;
  }
};

// Brute force: every sphere and every periodic image within a few periods, at every grid point.
std::vector<double> brute_force(const Spheres &s, const layer::Grid &g, double substrate, double lo, double hi) {
  std::vector<double> h(g.size(), 0.0);
  const bool periodic = lo != hi;
  for (std::uint32_t iy = 0; iy < g.ny; ++iy)
    for (std::uint32_t ix = 0; ix < g.nx; ++ix) {
      const double px = g.x0 + (ix + 0.5) * g.cell, py = g.y0 + (iy + 0.5) * g.cell;
      double best = 0;
      for (std::size_t i = 0; i < s.x.size(); ++i)
        for (int k = periodic ? -3 : 0; k <= (periodic ? 3 : 0); ++k) {
          const double dx = px - s.x[i], dy = py - (s.y[i] + k * (hi - lo));
          const double d2 = dx * dx + dy * dy;
          if (d2 <= s.r[i] * s.r[i]) best = std::max(best, s.z[i] + std::sqrt(s.r[i] * s.r[i] - d2) - substrate);
        }
      h[iy * g.nx + ix] = best;
    }
  return h;
}

TEST(LayerGrid, CellsPerAxisAreRoundedExtentOverCell) {
  const double region[4] = {0, 1.0e-3, 2e-3, 2.6e-3};
  layer::Grid g = layer::make_grid(region, 0.3e-3);  // 3.33 -> 3 and 2.0 -> 2
  EXPECT_EQ(g.nx, 3u);
  EXPECT_EQ(g.ny, 2u);
  EXPECT_DOUBLE_EQ(g.x0, 0.5e-3 - 1.5 * 0.3e-3);  // centred on the region
  EXPECT_DOUBLE_EQ(g.y0, 2.3e-3 - 0.3e-3);
  g = layer::make_grid(region, 0.35e-3);  // 2.857 -> 3 and 1.714 -> 2
  EXPECT_EQ(g.nx, 3u);
  EXPECT_EQ(g.ny, 2u);
  g = layer::make_grid(region, 0.45e-3);  // 2.22 -> 2 and 1.33 -> 1
  EXPECT_EQ(g.nx, 2u);
  EXPECT_EQ(g.ny, 1u);
  g = layer::make_grid(region, 5e-3);  // less than half a cell: still one cell
  EXPECT_EQ(g.nx, 1u);
  EXPECT_EQ(g.ny, 1u);
  const double inverted[4] = {1e-3, 0, 0, 1e-3};
  EXPECT_THROW(layer::make_grid(inverted, 1e-4), std::invalid_argument);
}

TEST(LayerGrid, DefaultCellIsOneFifthOfTheMeanDiameter) {
  Spheres s;
  s.add(1e-3, 1e-3, 100e-6, 100e-6);
  s.add(2e-3, 1e-3, 150e-6, 150e-6);  // mean diameter 250 um
  const auto result = layer::characterise_layer(s.input(0, 5e-3, 0, 2.5e-3), 0.0);
  EXPECT_DOUBLE_EQ(result.metrics.cell, 50e-6);
  EXPECT_EQ(result.grid.nx, 100u);
  EXPECT_EQ(result.grid.ny, 50u);
}

TEST(LayerHeightmap, RandomPolydisperseLayerMatchesBruteForce) {
  std::mt19937_64 rng(12345);
  std::uniform_real_distribution<double> ux(-0.4e-3, 3.4e-3), uy(-0.4e-3, 2.4e-3), ur(60e-6, 160e-6), uz(0, 400e-6);
  Spheres s;
  for (int i = 0; i < 400; ++i) {
    const double r = ur(rng);
    s.add(ux(rng), uy(rng), 10e-6 + r + uz(rng), r);
  }
  const double substrate = 10e-6;
  for (bool periodic : {false, true}) {
    sm_layer_input_v1 in = s.input(0.1e-3, 2.9e-3, 0.0, 2.0e-3);
    in.substrate_z = substrate;
    if (periodic) in.periodic_y[0] = 0.0, in.periodic_y[1] = 2.0e-3;
    const auto result = layer::characterise_layer(in, 17e-6);
    const auto ref = brute_force(s, result.grid, substrate, in.periodic_y[0], in.periodic_y[1]);
    ASSERT_EQ(result.height.size(), ref.size());
    std::size_t covered = 0;
    for (std::size_t k = 0; k < ref.size(); ++k) {
      ASSERT_NEAR(result.height[k], ref[k], 1e-12 * 1e-3) << "point " << k << " periodic " << periodic;
      covered += result.covered[k];
    }
    EXPECT_GT(covered, ref.size() / 2);  // the scene is dense enough to mean something
  }
}

TEST(LayerHeightmap, IndependentOfTheThreadCount) {
  std::mt19937_64 rng(99);
  std::uniform_real_distribution<double> u(0, 2e-3);
  Spheres s;
  for (int i = 0; i < 300; ++i) s.add(u(rng), u(rng), 125e-6 + 0.2 * u(rng), 125e-6);
  const sm_layer_input_v1 in = s.input(0, 2e-3, 0, 2e-3);
  const int threads = omp_get_max_threads();
  omp_set_num_threads(1);
  const auto serial = layer::characterise_layer(in, 10e-6);
  omp_set_num_threads(std::max(2, threads));
  const auto parallel = layer::characterise_layer(in, 10e-6);
  omp_set_num_threads(threads);
  EXPECT_EQ(serial.height, parallel.height);  // bit for bit
  EXPECT_EQ(layer::metrics_json(serial), layer::metrics_json(parallel));
}

TEST(LayerHeightmap, PeriodicImagesCoverAcrossTheStripEdge) {
  // One sphere straddling y_hi of a strip: in the strip, its image completes the disk at y_lo.
  const double r = 125e-6, cell = 5e-6, L = 1e-3;
  Spheres s;
  s.add(0.5e-3, L - 0.3 * r, r, r);
  sm_layer_input_v1 in = s.input(0, 1e-3, 0, L);
  const auto open = layer::characterise_layer(in, cell);
  in.periodic_y[0] = 0;
  in.periodic_y[1] = L;
  const auto strip = layer::characterise_layer(in, cell);
  const double area = L * 1e-3, disk = pi * r * r;
  // Point counting on a 5 um grid: the disk's area is known to within its perimeter x cell.
  const double tol = 2 * pi * r * cell / area;
  EXPECT_NEAR(strip.metrics.coverage, disk / area, tol);
  EXPECT_LT(open.metrics.coverage, 0.8 * disk / area);
  // Solid: the clipped sphere plus its clipped image make the whole sphere, exactly.
  EXPECT_NEAR(strip.metrics.solid_thickness * area, 4 * pi / 3 * r * r * r, 1e-12 * r * r * r);
  EXPECT_EQ(strip.metrics.particles_in_region, 1u);  // the image's centre lies outside
}

TEST(LayerMetrics, EmptyRegionGivesZerosAndExplicitNulls) {
  Spheres s;
  s.add(5e-3, 5e-3, 125e-6, 125e-6);  // far from the region
  sm_layer_input_v1 in = s.input(0, 1e-3, 0, 1e-3);
  in.speed = 0.1;
  in.gap = 500e-6;
  const auto result = layer::characterise_layer(in, 25e-6);
  EXPECT_EQ(result.metrics.mean_height, 0.0);
  EXPECT_EQ(result.metrics.rq, 0.0);
  EXPECT_EQ(result.metrics.vs, 0.0);
  EXPECT_EQ(result.metrics.coverage, 0.0);
  EXPECT_EQ(result.metrics.particles_in_region, 0u);
  EXPECT_TRUE(std::isnan(result.metrics.packing_fraction));
  EXPECT_DOUBLE_EQ(result.metrics.largest_bare_patch, 1e-6);  // the whole region is one bare patch
  ASSERT_FALSE(result.warnings.empty());

  const std::string text = layer::metrics_json(result);
  EXPECT_EQ(text.find("nan"), std::string::npos);
  EXPECT_EQ(text.find("NaN"), std::string::npos);
  const auto j = nlohmann::json::parse(text);
  EXPECT_TRUE(j["metrics"]["packing_fraction"].is_null());
  EXPECT_EQ(j["metrics"]["mean_height"].get<double>(), 0.0);
  EXPECT_EQ(j["units"]["largest_bare_patch"], "m^2");
  EXPECT_FALSE(j["warnings"].empty());
}

TEST(LayerMetrics, SpreadRateAndPackingOverTheGap) {
  // A single sphere, exactly inside: solid = 4/3 pi r^3, so every derived metric has a closed form.
  const double r = 125e-6, side = 1e-3, area = side * side, U = 0.07, gap = 0.5e-3;
  Spheres s;
  s.add(0.5e-3, 0.5e-3, r, r);
  sm_layer_input_v1 in = s.input(0, side, 0, side);
  in.speed = U;
  in.gap = gap;
  auto result = layer::characterise_layer(in, 10e-6);
  const double solid = 4 * pi / 3 * r * r * r;
  EXPECT_NEAR(result.metrics.solid_thickness, solid / area, 1e-12 * solid / area);
  EXPECT_NEAR(result.metrics.packing_fraction_gap, solid / (area * gap), 1e-12);
  EXPECT_DOUBLE_EQ(result.metrics.vs, result.metrics.mean_height * U);
  EXPECT_NEAR(result.metrics.packing_fraction, solid / (result.metrics.mean_height * area), 1e-12);
  EXPECT_EQ(result.metrics.particles_in_region, 1u);
  EXPECT_TRUE(result.warnings.empty());

  in.speed = nan;
  in.gap = nan;
  result = layer::characterise_layer(in, 10e-6);
  const auto j = nlohmann::json::parse(layer::metrics_json(result));
  EXPECT_TRUE(j["metrics"]["vs"].is_null());
  EXPECT_TRUE(j["metrics"]["packing_fraction_gap"].is_null());
  EXPECT_EQ(j["units"]["vs"], "m^2/s");
}

TEST(LayerMetrics, BarePatchesConnectOnlyThroughEdges) {
  // 0 = bare. The two bare points at (0,0) and (1,1) touch only diagonally: two patches of 1 and 5.
  const std::vector<std::uint8_t> covered = {0, 1, 1, 1,   //
                                             1, 0, 0, 0,   //
                                             1, 1, 0, 1,   //
                                             1, 1, 0, 1};  //
  EXPECT_EQ(layer::largest_bare_patch_points(covered, 4, 4), 5u);
}

TEST(LayerMetrics, RejectsNonFiniteSpheres) {
  Spheres s;
  s.add(nan, 0, 0, 1e-4);
  EXPECT_THROW(layer::characterise_layer(s.input(0, 1e-3, 0, 1e-3), 1e-5), std::invalid_argument);
}

}  // namespace
