// The verify stage through the real binary, on a tiny version of workflows/quickstart_verify.yaml
// (tests/workflow/data/verify/tiny_verify.yaml, with replicated design points): map/verified.json
// holds the predicted value, its interval and the simulated runs of the optimum, its verdicts follow
// from those numbers, its runs are new heaps, and a second `spreadmap verify` recomputes nothing.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "workflow/process.hpp"
#include "workflow/run_files.hpp"

namespace fs = std::filesystem;
namespace t = spreadmap::test;

TEST(Verify, TheVerifiedOptimumHoldsItsPredictionItsRunsAndTheVerdict) {
  const fs::path workflow = fs::path(SPREADMAP_SOURCE_DIR) / "tests/workflow/data/verify/tiny_verify.yaml";
  const fs::path run = t::fresh_run_directory("spreadmap_verify");
  const auto first = t::run(
      {{"run", workflow.string(), "--out", run.string(), "--jobs", "2", "--only", "simulate,characterise,train,map"},
       {},
       {},
       {}});
  ASSERT_EQ(first.exit_code, 0) << first.describe();
  EXPECT_TRUE(t::contains(first.err, "simulate: 8 cases (4 points x 2 replicates)")) << first.err;

  auto runs = t::csv_columns(run / "metrics_replicates.csv");
  const std::string proposed_map = t::slurp(run / "map/map.png");  // as the map stage drew it
  const auto verify = t::run({{"verify", workflow.string(), "--out", run.string(), "--jobs", "2"}, {}, {}, {}});
  ASSERT_EQ(verify.exit_code, 0) << verify.describe();
  // verified.json: both targets share one optimum, checked once with 2 new runs.
  const auto verified = t::json_file(run / "map/verified.json");
  const auto optimum = t::json_file(run / "map/optimum.json");
  ASSERT_EQ(verified["points"].size(), 1u) << verified.dump(2);
  const auto &point = verified["points"][0];
  EXPECT_EQ(point["rq_max"].size(), 2u);
  for (std::size_t k = 0; k < 2; ++k)
    EXPECT_EQ(point["rq_max_met"][k].get<bool>(),
              point["metrics"]["rq"]["simulated_mean"].get<double>() <= point["rq_max"][k].get<double>());
  EXPECT_EQ(point["inputs"], optimum["optima"][0]["inputs"]);
  EXPECT_EQ(verified["replicates"], 2);
  bool all_inside = true;
  for (const std::string m : {"vs", "rq"}) {
    const auto &c = point["metrics"][m];
    const auto values = c["simulated"].get<std::vector<double>>();
    ASSERT_EQ(values.size(), 2u);
    const double mean = c["simulated_mean"], lo = c["interval"][0], hi = c["interval"][1];
    const double predicted = c["predicted"], sd = c["predicted_std"];
    EXPECT_GE(mean, *std::min_element(values.begin(), values.end()));
    EXPECT_LE(mean, *std::max_element(values.begin(), values.end()));
    EXPECT_NEAR(mean, (values[0] + values[1]) / 2, 1e-12 * std::abs(mean));
    EXPECT_NEAR(c["simulated_std"].get<double>(), std::abs(values[0] - values[1]) / std::sqrt(2.0), 1e-9 * mean);
    EXPECT_GT(sd, 0.0);
    EXPECT_NEAR(lo, predicted - 2 * sd, 1e-12 * std::abs(predicted));
    EXPECT_NEAR(hi, predicted + 2 * sd, 1e-12 * std::abs(predicted));
    EXPECT_EQ(c["inside"].get<bool>(), lo <= mean && mean <= hi) << m;
    all_inside = all_inside && c["inside"].get<bool>();
    // the runs are new heaps: not any design case's layer
    for (double v : values)
      for (const auto &cell : runs[m]) EXPECT_NE(v, std::stod(cell));
  }
  EXPECT_EQ(point["verified"].get<bool>(), all_inside);
  EXPECT_EQ(verified["verified"].get<bool>(), all_inside);
  // on the border of the box (U 70..100 mm/s, omega -20..20 rad/s) exactly when the log says so
  const double U = point["inputs"]["U"], omega = point["inputs"]["omega"];
  const bool border = std::abs(U - 0.07) < 1e-12 || std::abs(U - 0.1) < 1e-12 || std::abs(std::abs(omega) - 20) < 1e-9;
  EXPECT_EQ(point["at_edge"].get<bool>(), border) << point.dump(2);
  EXPECT_EQ(t::contains(verify.err, "at the edge of the explored range: widen U or ω"), border) << verify.err;
#ifdef SPREADMAP_TEST_FIGURES
  // map.png drawn again with the optimum marked as checked: not the proposed map's picture
  EXPECT_GT(t::slurp(run / "map/map.png").size(), 1000u);
  EXPECT_NE(t::slurp(run / "map/map.png"), proposed_map);
#endif

  // `spreadmap verify` alone: every run finished, nothing recomputed, the same answer.
  const auto again = t::run({{"verify", workflow.string(), "--out", run.string()}, {}, {}, {}});
  ASSERT_EQ(again.exit_code, 0) << again.describe();
  EXPECT_TRUE(t::contains(again.err, "verify: 1 points x 2 runs, 0 to run, 2 finished already")) << again.err;
  EXPECT_EQ(t::json_file(run / "map/verified.json"), verified);
  if (!HasFailure()) fs::remove_all(run);
}
