// host/analysis/replicate_summary: the per-point summary of replicated runs (mean and sample standard
// deviation against hand values, undefined cells left out) and the known noise it gives a model.
#include <gtest/gtest.h>

#include <cmath>

#include "host/analysis/replicate_summary.hpp"

namespace sa = spreadmap::analysis;

TEST(AnalysisReplicates, EachPointGetsTheMeanAndSampleStdOfItsReplicates) {
  sa::Table runs({"case", "U", "vs", "rq", "point", "replicate"}, "runs");
  runs.add_row(std::vector<std::string>{"c000", "0.04", "1", "10", "c000", "0"});
  runs.add_row(std::vector<std::string>{"c000_r1", "0.04", "2", "", "c000", "1"});  // rq undefined here
  runs.add_row(std::vector<std::string>{"c000_r2", "0.04", "6", "14", "c000", "2"});
  runs.add_row(std::vector<std::string>{"c001", "0.07", "5", "7", "c001", "0"});
  const sa::Table t = sa::summarise_replicates(runs, "point", {"U"}, {"vs", "rq"}, "metrics.csv");
  ASSERT_EQ(t.columns(), (std::vector<std::string>{"case", "U", "vs", "vs_std", "rq", "rq_std", "replicates"}));
  ASSERT_EQ(t.rows(), 2u);
  EXPECT_EQ(t.text(0, 0), "c000");
  EXPECT_EQ(t.number(0, 1), 0.04);
  EXPECT_EQ(t.number(0, 2), 3.0);                      // (1 + 2 + 6) / 3
  EXPECT_NEAR(t.number(0, 3), std::sqrt(7.0), 1e-15);  // (4 + 1 + 9) / 2
  EXPECT_EQ(t.number(0, 4), 12.0);                     // the undefined cell is left out
  EXPECT_NEAR(t.number(0, 5), std::sqrt(8.0), 1e-15);  // (4 + 4) / 1
  EXPECT_EQ(t.number(0, 6), 3.0);
  EXPECT_EQ(t.number(1, 2), 5.0);
  EXPECT_EQ(t.text(1, 3), "") << "no standard deviation of one value";
  EXPECT_EQ(t.number(1, 6), 1.0);

  // the noise of each mean a model may take: std^2 / replicates, 0 where it is not known
  const Eigen::MatrixXd v = sa::replicate_noise_variance(t, {"rq", "vs"}, {0, 1});
  EXPECT_NEAR(v(0, 0), 8.0 / 3.0, 1e-14);
  EXPECT_NEAR(v(0, 1), 7.0 / 3.0, 1e-14);
  EXPECT_EQ(v(1, 0), 0.0);
  EXPECT_EQ(v(1, 1), 0.0);
  EXPECT_EQ(sa::replicate_noise_variance(runs, {"vs"}, {0, 1}), Eigen::MatrixXd::Zero(2, 1)) << "no replicates column";
}
