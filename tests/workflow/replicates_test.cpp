// Replicates through the real binary (tests/workflow/data/replicates/tiny_replicates.yaml): the
// replicates of a point spread different heaps, metrics.csv holds per point the mean and the standard
// deviation of its per-replicate rows (kept in metrics_replicates.csv), the GP takes that scatter as
// known noise, and a second run recomputes nothing.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "workflow/process.hpp"
#include "workflow/run_files.hpp"

namespace fs = std::filesystem;
namespace t = spreadmap::test;

TEST(Replicates, SpreadDifferentHeapsAndMetricsHoldTheirMeanAndStd) {
  const fs::path workflow = fs::path(SPREADMAP_SOURCE_DIR) / "tests/workflow/data/replicates/tiny_replicates.yaml";
  const fs::path run = t::fresh_run_directory("spreadmap_replicates");
  const auto first = t::run({{"run", workflow.string(), "--out", run.string(), "--jobs", "2"}, {}, {}, {}});
  ASSERT_EQ(first.exit_code, 0) << first.describe();
  EXPECT_TRUE(t::contains(first.err, "simulate: 8 cases (4 points x 2 replicates), 8 to run")) << first.err;
  // Replicates: a heap of their own (another seed, other positions), the same inputs.
  const auto scene0 = t::json_file(run / "cases/c000/scene.json"),
             scene1 = t::json_file(run / "cases/c000_r1/scene.json");
  EXPECT_NE(scene0["powder"]["seed"], scene1["powder"]["seed"]);
  EXPECT_NE(t::slurp(run / "cases/c000/state.vtp"), t::slurp(run / "cases/c000_r1/state.vtp"));

  // metrics.csv: per point, the mean and the sample standard deviation of its per-replicate rows.
  auto runs = t::csv_columns(run / "metrics_replicates.csv"), points = t::csv_columns(run / "metrics.csv");
  ASSERT_EQ(runs["case"].size(), 8u);
  ASSERT_EQ(points["case"].size(), 4u);
  for (std::size_t p = 0; p < 4; ++p) {
    EXPECT_EQ(points["replicates"][p], "2");
    for (const std::string m : {"vs", "rq", "mean_height"}) {
      std::vector<double> v;
      for (std::size_t r = 0; r < 8; ++r)
        if (runs["point"][r] == points["case"][p]) v.push_back(std::stod(runs[m][r]));
      ASSERT_EQ(v.size(), 2u) << points["case"][p];
      const double mean = (v[0] + v[1]) / 2, sd = std::abs(v[0] - v[1]) / std::sqrt(2.0);
      EXPECT_NEAR(std::stod(points[m][p]), mean, 1e-12 * std::abs(mean)) << m << " of " << points["case"][p];
      EXPECT_NEAR(std::stod(points[m + "_std"][p]), sd, 1e-9 * std::abs(mean)) << m << " of " << points["case"][p];
      EXPECT_GT(sd, 0.0) << m << ": two heaps, two layers";
    }
  }
  EXPECT_EQ(t::json_file(run / "metrics.units.json")["vs_std"], "m^2/s");

  // The GP got the replicate scatter as known noise, and keeps it in its state.
  EXPECT_TRUE(t::contains(first.err, "replicate scatter of 4 rows is given to the model")) << first.err;
  EXPECT_EQ(t::json_file(run / "train/gp/model.json")["state"]["noise_var"].size(), 4u);

  // run again: every replicate finished, none recomputed, the same table
  const std::string table = t::slurp(run / "metrics.csv");
  const auto again = t::run({{"run", workflow.string(), "--out", run.string()}, {}, {}, {}});
  ASSERT_EQ(again.exit_code, 0) << again.describe();
  EXPECT_TRUE(t::contains(again.err, "8 cases (4 points x 2 replicates), 0 to run, 8 finished already")) << again.err;
  EXPECT_EQ(t::slurp(run / "metrics.csv"), table);
  if (!HasFailure()) fs::remove_all(run);
}
