// host/analysis: grid evaluation, the constrained optimum, the frontier and the report, on
// analytic models whose answers are known in closed form.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "host/analysis/cross_validation.hpp"
#include "host/analysis/grid.hpp"
#include "host/analysis/optimum.hpp"
#include "host/analysis/report.hpp"

namespace sm = spreadmap;
namespace sa = spreadmap::analysis;

namespace {
// vs = x0 - 0.1 (x1 - 0.3)^2, rq = x0^2 + (x1 - 0.3)^2 on [0, 1] x [-1, 1]: the largest vs with
// rq <= t is at x0 = sqrt(t), x1 = 0.3 (the vs term breaks the tie along x1). Optional constant
// std for the probability check.
struct Analytic : sa::Model {
  double sigma = 0;
  void fit(const Eigen::MatrixXd &, const Eigen::MatrixXd &) override {}
  sa::Prediction predict(const Eigen::MatrixXd &x) const override {
    sa::Prediction p;
    p.mean.resize(x.rows(), 2);
    p.mean.col(0) = x.col(0).array() - 0.1 * (x.col(1).array() - 0.3).square();
    p.mean.col(1) = x.col(0).array().square() + (x.col(1).array() - 0.3).square();
    if (sigma > 0) p.std = Eigen::MatrixXd::Constant(x.rows(), 2, sigma);
    return p;
  }
  bool has_std() const override { return sigma > 0; }
  nlohmann::json state() const override { return {}; }
  void load(const nlohmann::json &) override {}
  nlohmann::json fit_info() const override { return {}; }
};
const std::vector<sa::Axis> box = {{"U", 0, 1, 101}, {"omega", -1, 1, 81}};
}  // namespace

TEST(AnalysisGrid, PointsCoverTheBoxWithExactEnds) {
  const Eigen::MatrixXd x = sa::grid_points(box);
  ASSERT_EQ(x.rows(), 101 * 81);
  EXPECT_EQ(x(0, 0), 0.0);
  EXPECT_EQ(x(0, 1), -1.0);
  EXPECT_EQ(x(80, 1), 1.0);  // second axis fastest
  EXPECT_EQ(x(81, 0), 0.01);
  EXPECT_EQ(x(x.rows() - 1, 0), 1.0);
  EXPECT_EQ(sa::default_grid_points(2), (std::vector<std::size_t>{101, 81}));
  const Analytic m;
  const sa::Table t = sa::evaluate_grid(m, box, {"vs", "rq"}).to_table();
  EXPECT_EQ(t.columns(), (std::vector<std::string>{"U", "omega", "vs", "rq"}));
}

TEST(AnalysisOptimum, FindsTheConstrainedMaximumWithinOneCell) {
  Analytic m;
  const sa::GridMap g = sa::evaluate_grid(m, box, {"vs", "rq"});
  for (double target : {0.2, 0.05, 0.6}) {
    const sa::Optimum o = sa::find_optimum(g, 0, 1, target, {0.5});
    ASSERT_TRUE(o.found);
    EXPECT_LE(o.rq, target);
    EXPECT_LE(std::abs(o.x[0] - std::sqrt(target)), 0.01) << target;  // one cell in U
    EXPECT_LE(std::abs(o.x[1] - 0.3), 0.025) << target;               // one cell in omega
    EXPECT_EQ(o.probability, -1.0);
  }
  EXPECT_FALSE(sa::find_optimum(g, 0, 1, -1.0, {0.5}).found);
}

TEST(AnalysisOptimum, ProbabilityOfMeetingTheTargetIsTheNormalLaw) {
  Analytic m;
  m.sigma = 0.01;
  const sa::GridMap g = sa::evaluate_grid(m, box, {"vs", "rq"});
  const sa::Optimum o = sa::find_optimum(g, 0, 1, 0.2, {0.5});
  const double z = (0.2 - o.rq) / 0.01;
  EXPECT_NEAR(o.probability, 0.5 * std::erfc(-z / std::sqrt(2.0)), 1e-15);
  EXPECT_GE(o.probability, 0.5);  // the point meets the target by its mean
  EXPECT_EQ(o.to_json({"U", "omega"})["inputs"]["omega"].get<double>(), o.x[1]);
}

TEST(AnalysisOptimum, AModelWithoutStdTakesTheFallbackSpreadOrIsRefusedAboveOneHalf) {
  const Analytic m;  // no std
  const sa::GridMap g = sa::evaluate_grid(m, box, {"vs", "rq"});
  EXPECT_THROW(sa::find_optimum(g, 0, 1, 0.2, {0.9}), std::invalid_argument);
  EXPECT_THROW(sa::find_optimum(g, 0, 1, 0.2, {0.4}), std::invalid_argument);
  const sa::Optimum o = sa::find_optimum(g, 0, 1, 0.2, {0.9, 0.01, "cross-validation"});
  ASSERT_TRUE(o.found);
  EXPECT_EQ(o.std_source, "cross-validation");
  EXPECT_EQ(o.rq_std, 0.01);
  EXPECT_LE(o.rq + sa::normal_quantile(0.9) * 0.01, 0.2);
  EXPECT_GE(o.probability, 0.9);
  // the true curve: rq = 0.2 - 1.2816 x 0.01 at x1 = 0.3, so x0 = sqrt(that), within one cell
  EXPECT_LE(std::abs(o.x[0] - std::sqrt(0.2 - sa::normal_quantile(0.9) * 0.01)), 0.01);
  EXPECT_EQ(o.to_json({"U", "omega"})["rq_std_source"], "cross-validation");
}

TEST(AnalysisOptimum, FrontierIsAMonotoneStaircaseOnTheTrueCurve) {
  Analytic m;
  const sa::GridMap g = sa::evaluate_grid(m, box, {"vs", "rq"});
  const sa::Table f = sa::frontier(g, 0, 1);
  ASSERT_GE(f.rows(), 40u);
  const auto level = f.numbers("rq_level"), vs = f.numbers("vs_max"), rq = f.numbers("rq");
  for (std::size_t i = 0; i < f.rows(); ++i) {
    if (i) {
      EXPECT_GE(vs[i], vs[i - 1]);
    }
    EXPECT_LE(rq[i], level[i]);
    EXPECT_LE(std::abs(vs[i] - std::min(1.0, std::sqrt(level[i]))), 0.01 + 1e-12) << "level " << level[i];
  }
}

TEST(AnalysisReport, ScoresEachSplitSeparately) {
  // A model that is exact on U and off by a known amount on rq: rq_pred - rq_true = 0.01 everywhere.
  struct Offset : Analytic {
    sa::Prediction predict(const Eigen::MatrixXd &x) const override {
      sa::Prediction p = Analytic::predict(x);
      p.mean.col(1).array() += 0.01;
      return p;
    }
  } m;
  const Eigen::MatrixXd x = sa::grid_points({{"U", 0, 1, 3}, {"omega", -1, 1, 3}});
  const Eigen::MatrixXd y = Analytic().predict(x).mean;
  const sa::Split s{{0, 1, 2, 3, 4, 5}, {6, 7, 8}};
  const sa::Report r = sa::make_report(m, x, y, s, {"vs", "rq"});
  EXPECT_EQ(r.outputs[0].nrmse_train, 0.0);
  EXPECT_NEAR(r.outputs[0].r_train, 1.0, 1e-15);
  EXPECT_NEAR(r.outputs[1].r_test, 1.0, 1e-12);  // a constant offset keeps R = 1
  // rq on test rows (x0 = 1): 1 + (x1 - 0.3)^2 = 2.69, 1.09, 1.49 for x1 = -1, 0, 1 -> range 1.6.
  EXPECT_NEAR(r.outputs[1].nrmse_test, 100 * 0.01 / 1.6, 1e-12);
  EXPECT_EQ(r.parity.rows(), 9u);
  EXPECT_EQ(r.to_json()["outputs"][1]["name"], "rq");
  // rq on train rows (x0 = 0, 0.5): from 0.09 at (0, 0) to 1.94 at (0.5, -1) -> range 1.85.
  EXPECT_NEAR(r.outputs[1].nrmse_train, 100 * 0.01 / 1.85, 1e-12);
  EXPECT_NEAR(r.outputs[0].r_test, 1.0, 1e-15);
}

TEST(AnalysisReport, NoPearsonROnTwoRowsAndTheReportSaysWhy) {
  const Eigen::MatrixXd x = sa::grid_points({{"U", 0, 1, 3}, {"omega", -1, 1, 3}});
  const Eigen::MatrixXd y = Analytic().predict(x).mean;
  const sa::Split s{{0, 1, 2, 3, 4, 5, 6}, {7, 8}};
  const sa::Report r = sa::make_report(Analytic(), x, y, s, {"vs", "rq"});
  EXPECT_TRUE(std::isnan(r.outputs[0].r_test));  // through 2 points R is +-1 whatever the model
  EXPECT_NEAR(r.outputs[0].r_train, 1.0, 1e-15);
  const auto j = r.to_json();
  EXPECT_TRUE(j["outputs"][1]["r_test"].is_null());
  EXPECT_EQ(j["outputs"][1]["nrmse_test"].get<double>(), 0.0);
  ASSERT_EQ(j["notes"].size(), 1u);
  EXPECT_NE(j["notes"][0].get<std::string>().find("r_test is null: 2 rows"), std::string::npos) << j["notes"];
}

namespace {
// Predicts the mean of the outputs it was fitted to, everywhere: its out-of-fold errors are known.
struct MeanModel : sa::Model {
  Eigen::RowVectorXd mean;
  void fit(const Eigen::MatrixXd &, const Eigen::MatrixXd &y) override { mean = y.colwise().mean(); }
  sa::Prediction predict(const Eigen::MatrixXd &x) const override {
    return {mean.replicate(x.rows(), 1), Eigen::MatrixXd()};
  }
  bool has_std() const override { return false; }
  nlohmann::json state() const override { return {}; }
  void load(const nlohmann::json &) override {}
  nlohmann::json fit_info() const override { return {}; }
};
}  // namespace

TEST(AnalysisCrossValidation, LeaveOneOutOfTheMeanIsKnownInClosedForm) {
  // Leaving row i out, the mean of the others misses y_i by (y_i - mean) n / (n - 1): the pooled
  // LOO RMSE is n / (n - 1) times the population standard deviation, and the out-of-fold
  // predictions fall as y_i rises (R = -1).
  const std::vector<double> values = {1.0, 2.0, 4.0, 7.0, 11.0, 16.0};
  const Eigen::Index n = Eigen::Index(values.size());
  Eigen::MatrixXd x(n, 1), y(n, 1);
  for (Eigen::Index i = 0; i < n; ++i) x(i, 0) = double(i), y(i, 0) = values[std::size_t(i)];
  const double mean = y.mean(), range = 15.0, k = double(n) / double(n - 1);
  const double sd_pop = std::sqrt((y.array() - mean).square().mean());
  std::vector<std::size_t> rows(values.size());
  for (std::size_t i = 0; i < rows.size(); ++i) rows[i] = i;
  const auto cv = sa::cross_validate([] { return std::make_unique<MeanModel>(); }, x, y, rows,
                                     sa::k_fold(rows.size(), rows.size(), 3));
  for (Eigen::Index i = 0; i < n; ++i)
    EXPECT_NEAR(cv.predicted(i, 0), (y.sum() - y(i, 0)) / double(n - 1), 1e-12) << "row " << i;
  sa::Report r;
  r.outputs.push_back({});
  sa::score_cross_validation(r, cv, y);
  EXPECT_NEAR(r.outputs[0].nrmse_cv, 100 * k * sd_pop / range, 1e-10);
  EXPECT_NEAR(r.outputs[0].r_cv, -1.0, 1e-12);
  // per fold: 100 |y_i - mean| k / range; their sample standard deviation
  std::vector<double> folds;
  for (double v : values) folds.push_back(100 * std::abs(v - mean) * k / range);
  double fm = 0, fv = 0;
  for (double f : folds) fm += f / double(n);
  for (double f : folds) fv += (f - fm) * (f - fm) / double(n - 1);
  EXPECT_NEAR(r.outputs[0].nrmse_cv_sd, std::sqrt(fv), 1e-10);
  EXPECT_EQ(r.cv_folds, 6u);
  EXPECT_EQ(r.cv_rows, 6u);
}
