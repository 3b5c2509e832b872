// host/analysis: CSV tables, splits and the Table-4 scores against hand-computed values.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <set>

#include "host/analysis/scores.hpp"
#include "host/analysis/split.hpp"
#include "host/analysis/validation.hpp"
#include "host/analysis/table.hpp"

namespace sm = spreadmap;
namespace sa = spreadmap::analysis;

TEST(AnalysisScores, NrmseAndPearsonMatchHandValues) {
  Eigen::VectorXd t(4), p(4);
  t << 1, 2, 3, 4;
  p << 1.1, 1.9, 3.2, 3.8;
  // errors 0.1, -0.1, 0.2, -0.2: RMSE = sqrt(0.1 / 4) = 0.158114; range 3 -> 5.27046 %.
  EXPECT_NEAR(sa::rmse(t, p), std::sqrt(0.025), 1e-15);
  EXPECT_NEAR(sa::nrmse_percent(t, p), 5.270462766947303, 1e-12);
  // sum(da db) = 4.7, sum(da^2) = 5, sum(db^2) = 4.5 -> R = 4.7 / sqrt(22.5).
  EXPECT_NEAR(sa::pearson(t, p), 4.7 / std::sqrt(22.5), 1e-15);
  EXPECT_NEAR(sa::pearson(t, -p), -4.7 / std::sqrt(22.5), 1e-15);
  EXPECT_TRUE(std::isnan(sa::pearson(t, Eigen::VectorXd::Constant(4, 2.0))));
  EXPECT_TRUE(std::isnan(sa::nrmse_percent(Eigen::VectorXd::Constant(4, 2.0), p)));
}

TEST(AnalysisTable, CsvRoundTripIsExactAndLookupIgnoresCase) {
  const std::string text =
      "case, U ,omega,\"Vs, spread\",split\nc000,0.04,-20,1.25e-05,train\n\nc001,0.1,20,\"2.5e-05\",TEST\n";
  const sa::Table t = sa::Table::parse_csv(text, "metrics.csv");
  ASSERT_EQ(t.rows(), 2u);
  EXPECT_EQ(t.column("u"), 1u);
  EXPECT_EQ(t.column("OMEGA"), 2u);
  EXPECT_EQ(t.numbers("vs, SPREAD")[1], 2.5e-05);
  const auto path = (std::filesystem::temp_directory_path() / "analysis_table_test.csv").string();
  sa::Table out({"x", "y"});
  const double awkward = 0.1 + 0.2, tiny = 5e-324;
  out.add_row(std::vector<double>{awkward, tiny});
  out.add_row(std::vector<double>{-1.0 / 3.0, 1e300});
  out.write_csv(path);
  const sa::Table back = sa::Table::read_csv(path);
  EXPECT_EQ(back.numbers("x")[0], awkward);
  EXPECT_EQ(back.numbers("y")[0], tiny);
  EXPECT_EQ(back.numbers("X")[1], -1.0 / 3.0);
  std::filesystem::remove(path);
}

TEST(AnalysisTable, ErrorsNameFileLineAndColumn) {
  const sa::Table t = sa::Table::parse_csv("a,b\n1,2\n3,oops\n", "m.csv");
  try {
    t.numbers("b");
    FAIL() << "expected an error";
  } catch (const std::runtime_error &e) {
    EXPECT_NE(std::string(e.what()).find("m.csv:3: column 2 ('b'): 'oops' is not a number"), std::string::npos)
        << e.what();
  }
  try {
    t.column("c");
    FAIL();
  } catch (const std::runtime_error &e) {
    EXPECT_NE(std::string(e.what()).find("no column 'c'; the columns are: a, b"), std::string::npos) << e.what();
  }
  EXPECT_THROW(sa::Table::parse_csv("a,b\n1,2,3\n", "m.csv"), std::runtime_error);
  EXPECT_THROW(sa::Table::parse_csv("a,A\n", "m.csv"), std::runtime_error);
  EXPECT_THROW(sa::Table::read_csv("/nonexistent/metrics.csv"), std::runtime_error);
}

TEST(AnalysisSplit, StudySplitIs35To10AndSeeded) {
  const sa::Split s = sa::study_split(45, 7);
  EXPECT_EQ(s.train.size(), 35u);
  EXPECT_EQ(s.test.size(), 10u);
  std::set<std::size_t> all(s.train.begin(), s.train.end());
  all.insert(s.test.begin(), s.test.end());
  EXPECT_EQ(all.size(), 45u);
  EXPECT_EQ(sa::study_split(45, 7).test, s.test);
  EXPECT_NE(sa::study_split(45, 8).test, s.test);
  EXPECT_EQ(sa::study_split(9).test.size(), 2u);    // 9 x 10/45 = 2
  EXPECT_EQ(sa::study_split(4).test.size(), 2u);    // at least 2 test rows, 2 training rows
  EXPECT_EQ(sa::study_split(90).test.size(), 20u);  // same share
  EXPECT_THROW(sa::study_split(3), std::invalid_argument);
}

TEST(AnalysisSplit, KFoldPartitionsAndColumnSplit) {
  const auto folds = sa::k_fold(23, 5, 3);
  std::vector<int> seen(23, 0);
  for (const auto &f : folds) {
    EXPECT_EQ(f.train.size() + f.test.size(), 23u);
    for (auto r : f.test) ++seen[r];
  }
  EXPECT_TRUE(std::all_of(seen.begin(), seen.end(), [](int n) { return n == 1; }));
  const sa::Table t = sa::Table::parse_csv("x,split\n1,train\n2,Test\n3,train\n4,train\n", "s.csv");
  const sa::Split s = sa::split_from_column(t, "SPLIT");
  EXPECT_EQ(s.train, (std::vector<std::size_t>{0, 2, 3}));
  EXPECT_EQ(s.test, (std::vector<std::size_t>{1}));
  EXPECT_EQ(sa::split_labels(s, 4), (std::vector<std::string>{"train", "test", "train", "train"}));
  EXPECT_THROW(sa::split_from_column(sa::Table::parse_csv("x,split\n1,tran\n", "s.csv"), "split"), std::runtime_error);
}

TEST(AnalysisValidation, ReadsEverySpellingAndChoosesBySize) {
  using K = sa::Validation::Kind;
  EXPECT_EQ(sa::parse_validation("holdout").kind, K::holdout);
  EXPECT_EQ(sa::parse_validation("study").kind, K::holdout);  // the former name
  EXPECT_EQ(sa::parse_validation("loo").kind, K::loo);
  EXPECT_EQ(sa::parse_validation("kfold:7").folds, 7u);
  EXPECT_EQ(sa::parse_validation("kfold", 4).folds, 4u);
  EXPECT_EQ(sa::parse_validation("column:fold").column, "fold");
  EXPECT_EQ(sa::parse_validation("column").column, "split");
  for (const char *bad : {"kfold:1", "kfold:x", "kfold:", "loo:3", "holdot", "column:"})
    EXPECT_THROW(sa::parse_validation(bad), std::invalid_argument) << bad;
  const auto automatic = sa::parse_validation("auto");
  EXPECT_EQ(sa::resolve_validation(automatic, 45).kind, K::holdout);  // the study's 35/10
  EXPECT_EQ(sa::resolve_validation(automatic, 40).kind, K::holdout);
  EXPECT_EQ(sa::resolve_validation(automatic, 39).kind, K::kfold);
  EXPECT_EQ(sa::resolve_validation(automatic, 12).folds, 5u);
  EXPECT_EQ(sa::resolve_validation(automatic, 11).kind, K::loo);
  EXPECT_EQ(sa::resolve_validation(automatic, 9).kind, K::loo);
  EXPECT_NE(sa::resolve_validation(automatic, 9).reason.find("9 usable rows"), std::string::npos);
  EXPECT_EQ(sa::resolve_validation(sa::parse_validation("kfold:3"), 45).kind, K::kfold);  // asked: kept
  for (const char *text : {"holdout", "loo", "kfold:3", "column:fold"})
    EXPECT_EQ(sa::spelling(sa::parse_validation(text)), text);
}
