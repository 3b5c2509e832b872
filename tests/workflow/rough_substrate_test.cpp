// A heap spread onto a rough substrate through the real binary (tests/workflow/data/rough/one_heap.yaml):
// the state keeps the substrate's fixed spheres exactly where the set-up put them, with the requested
// R_q of their tops; the spreader ran at the mean plane + its gap; every powder sphere is accounted
// for; the layer metrics count the powder only.
#include <gtest/gtest.h>

#include <cmath>

#include "engine/vtp_io.hpp"
#include "workflow/process.hpp"
#include "workflow/run_files.hpp"
#include "workflow/spreading/substrate_roughness.hpp"
#include "workflow/spreading/layer_feed.hpp"

namespace fs = std::filesystem;
namespace sm = spreadmap;
namespace t = spreadmap::test;

TEST(RoughSubstrate, AHeapSpreadOntoItLeavesTheSubstrateInPlaceAndIsMeasuredFromItsMeanPlane) {
  const fs::path workflow = fs::path(SPREADMAP_SOURCE_DIR) / "tests/workflow/data/rough/one_heap.yaml";
  const fs::path run = t::fresh_run_directory("spreadmap_rough");
  const auto r = t::run({{"run", workflow.string(), "--out", run.string()}, {}, {}, {}});
  ASSERT_EQ(r.exit_code, 0) << r.describe();
  const fs::path c = run / "cases/c000";

  const sm::Scene scene = sm::read_scene_file(c / "scene.json");
  const auto substrate = sm::substrate_spheres(scene);
  ASSERT_EQ(substrate.size(), 80u * 5u);
  const auto state = sm::engine::read_vtp(c / "state.vtp").particles;
  ASSERT_EQ(state.fixed.size(), state.size());
  std::size_t fixed = 0;
  double mean = 0, sq = 0;
  for (std::size_t i = 0; i < state.size(); ++i) {
    if (!state.fixed[i]) continue;
    ++fixed;
    const std::uint32_t id = state.id[i];  // the set-up numbers the substrate first
    ASSERT_LT(id, substrate.size());
    EXPECT_EQ(state.x[i], substrate.x[id]);
    EXPECT_EQ(state.y[i], substrate.y[id]);
    EXPECT_EQ(state.z[i], substrate.z[id]) << "a fixed sphere moved";
    mean += (state.z[i] + state.radius[i]) / double(substrate.size());
  }
  EXPECT_EQ(fixed, substrate.size());
  for (std::size_t i = 0; i < state.size(); ++i)
    if (state.fixed[i]) sq += std::pow(state.z[i] + state.radius[i] - mean, 2);
  EXPECT_NEAR(std::sqrt(sq / double(fixed)), 20e-6, 1e-12 * 20e-6);

  const auto cj = t::json_file(c / "case.json");
  const double level = cj.at("substrate").at("mean_plane").get<double>();
  EXPECT_NEAR(level, mean, 1e-15);
  EXPECT_EQ(level, sm::substrate_level(scene));
  EXPECT_DOUBLE_EQ(cj.at("spreader").at("gap").get<double>(), 0.5e-3 + level) << "gap above the mean plane";
  const std::size_t powder = state.size() - fixed;
  EXPECT_EQ(powder, cj.at("particles_fed").get<std::size_t>() - cj.at("removed").get<std::size_t>() -
                        cj.at("removed_settling").get<std::size_t>());
  EXPECT_GT(cj.at("particles_fed").get<std::size_t>(), 150u);  // the heap, less those kept clear of the roller

  auto metrics = t::csv_columns(run / "metrics.csv");
  ASSERT_EQ(metrics["particles_in_region"].size(), 1u);
  EXPECT_LE(std::stoul(metrics["particles_in_region"][0]), powder) << "substrate spheres counted as layer";
  EXPECT_GT(std::stod(metrics["mean_height"][0]), 0.0);
}
