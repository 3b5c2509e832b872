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

  // characterise alone measures what the loop's last one did: the same rows, verify runs included
  const std::string metrics = t::slurp(run / "metrics.csv");
  const auto alone = t::run({{"run", workflow.string(), "--out", run.string(), "--only", "characterise"}, {}, {}, {}});
  ASSERT_EQ(alone.exit_code, 0) << alone.describe();
  EXPECT_EQ(t::slurp(run / "metrics.csv"), metrics);
  if (!HasFailure()) fs::remove_all(run);
}

// The verify loop (tiny_verify_loop.yaml: one run per design point, so the first model learns its
// noise from 4 rows only). Each round's verdict follows from its numbers, the loop stops at the
// first verified round, an unverified round's runs join metrics.csv as one replicated point and the
// refitted model's interval widens (the replicate scatter is now data); run again, nothing is
// simulated twice and the answer is the same.
TEST(Verify, TheLoopRefitsWithItsRunsUntilTheOptimumHolds) {
  const fs::path workflow = fs::path(SPREADMAP_SOURCE_DIR) / "tests/workflow/data/verify/tiny_verify_loop.yaml";
  const fs::path run = t::fresh_run_directory("spreadmap_verify_loop");
  const auto first = t::run({{"run", workflow.string(), "--out", run.string(), "--jobs", "2"}, {}, {}, {}});
  ASSERT_EQ(first.exit_code, 0) << first.describe();
  const auto verified = t::json_file(run / "map/verified.json");
  ASSERT_TRUE(verified.contains("earlier_rounds")) << verified.dump(2);
  const auto &earlier = verified["earlier_rounds"];
  const std::size_t rounds = verified["round"];
  ASSERT_EQ(earlier.size() + 1, rounds);
  ASSERT_GE(rounds, 2u) << "the first model verified at once: the loop was not exercised";
  for (const auto &r : earlier) EXPECT_FALSE(r["verified"].get<bool>());
  EXPECT_EQ(verified["verified"].get<bool>(), verified["points"][0]["verified"].get<bool>());
  EXPECT_TRUE(verified["verified"].get<bool>() || rounds == 3u);
  EXPECT_TRUE(t::contains(first.err, "round 1 of 3 not verified: its 3 runs join the training data")) << first.err;
  for (const auto &round : earlier)
    for (const auto &p : round["points"])
      for (const std::string m : {"vs", "rq"}) {
        const auto &c = p["metrics"][m];
        const double mean = c["simulated_mean"], lo = c["interval"][0], hi = c["interval"][1];
        EXPECT_EQ(c["inside"].get<bool>(), lo <= mean && mean <= hi);
      }
  // the unverified rounds' runs are rows of metrics.csv, one replicated point each round
  const auto table = t::csv_columns(run / "metrics.csv");
  std::size_t verify_rows = 0;
  for (std::size_t r = 0; r < table.at("case").size(); ++r)
    if (table.at("case")[r].rfind("verify/", 0) == 0) {
      ++verify_rows;
      EXPECT_EQ(table.at("replicates")[r], "3");
    }
  EXPECT_EQ(verify_rows, rounds - 1);
  EXPECT_EQ(table.at("case").size(), 4 + rounds - 1);
  // round 1's model knew no scatter: its R_q interval was narrower than the refitted one
  const double sd0 = earlier[0]["points"][0]["metrics"]["rq"]["predicted_std"];
  const double sd1 = (rounds == 2 ? verified : earlier[1])["points"][0]["metrics"]["rq"]["predicted_std"];
  EXPECT_GT(sd1, sd0);
  // the rounds' runs are different heaps
  const auto v0 = earlier[0]["points"][0]["metrics"]["rq"]["simulated"].get<std::vector<double>>();
  const auto v1 =
      (rounds == 2 ? verified : earlier[1])["points"][0]["metrics"]["rq"]["simulated"].get<std::vector<double>>();
  for (double a : v0)
    for (double b : v1) EXPECT_NE(a, b);

  const auto again = t::run({{"run", workflow.string(), "--out", run.string()}, {}, {}, {}});
  ASSERT_EQ(again.exit_code, 0) << again.describe();
  EXPECT_FALSE(t::contains(again.err, "to run, 0 finished")) << again.err;
  EXPECT_TRUE(t::contains(again.err, "verify: 1 points x 3 runs, 0 to run, 3 finished already")) << again.err;
  EXPECT_EQ(t::json_file(run / "map/verified.json"), verified);

  // characterise alone measures what the loop's last one did: the same rows, verify runs included
  const std::string metrics = t::slurp(run / "metrics.csv");
  const auto alone = t::run({{"run", workflow.string(), "--out", run.string(), "--only", "characterise"}, {}, {}, {}});
  ASSERT_EQ(alone.exit_code, 0) << alone.describe();
  EXPECT_EQ(t::slurp(run / "metrics.csv"), metrics);
  if (!HasFailure()) fs::remove_all(run);
}
