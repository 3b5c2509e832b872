// The map's optimum at a stated confidence: on a Gaussian process fitted to a synthetic process with
// known noise, the largest V_s whose P(R_q <= target) >= 0.9 meets that probability, lies inside the
// set the mean rule accepts, and confidence 0.5 gives the mean rule's point bit for bit.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "host/analysis/grid.hpp"
#include "host/analysis/optimum.hpp"
#include "plugins/surrogate/gp/gp_model.hpp"

namespace sa = spreadmap::analysis;
using spreadmap::surrogate::GpModel;

namespace {

// V_s grows with U; R_q grows with U and falls with omega (SI units, the quickstart's box).
double true_vs(double u, double w) { return 3.3e-4 * u + 1e-7 * w; }
double true_rq(double u, double w) { return 95e-6 + 2.5e-4 * (u - 0.04) - 0.4e-6 * w; }
constexpr double noise_rq = 2e-6, noise_vs = 0.1e-6;  // [m], [m^2/s]

struct GpSurrogate : sa::Model {
  GpModel gp;
  void fit(const Eigen::MatrixXd &x, const Eigen::MatrixXd &y) override { gp.fit(x, y); }
  sa::Prediction predict(const Eigen::MatrixXd &x) const override {
    sa::Prediction p;
    p.mean = gp.predict(x, &p.std);
    return p;
  }
  bool has_std() const override { return true; }
  nlohmann::json state() const override { return {}; }
  void load(const nlohmann::json &) override {}
  nlohmann::json fit_info() const override { return {}; }
};

// 5 x 5 cases with the known noise added, fitted once for every test below.
const GpSurrogate &fitted() {
  static const GpSurrogate model = [] {
    GpSurrogate m;
    std::mt19937 rng(7);
    std::normal_distribution<double> unit(0, 1);
    Eigen::MatrixXd x(25, 2), y(25, 2);
    for (int i = 0; i < 5; ++i)
      for (int j = 0; j < 5; ++j) {
        const int r = 5 * i + j;
        x(r, 0) = 0.04 + 0.015 * i, x(r, 1) = -20 + 10 * j;
        y(r, 0) = true_vs(x(r, 0), x(r, 1)) + noise_vs * unit(rng);
        y(r, 1) = true_rq(x(r, 0), x(r, 1)) + noise_rq * unit(rng);
      }
    m.fit(x, y);
    return m;
  }();
  return model;
}

const std::vector<sa::Axis> box = {{"U", 0.04, 0.1, 61}, {"omega", -20, 20, 41}};
constexpr double target = 100e-6;  // binding: the mean rule stops inside the box

double probability(double mean, double std, double t) { return 0.5 * std::erfc(-(t - mean) / (std * std::sqrt(2.0))); }

}  // namespace

TEST(ConfidentOptimum, NormalQuantileIsExactAtTheMedianAndRightInTheTail) {
  EXPECT_EQ(sa::normal_quantile(0.5), 0.0);
  EXPECT_NEAR(sa::normal_quantile(0.9), 1.2815515655446004, 1e-12);
  EXPECT_NEAR(sa::normal_quantile(0.975), 1.9599639845400538, 1e-12);
  EXPECT_THROW(sa::normal_quantile(1.0), std::invalid_argument);
}

TEST(ConfidentOptimum, MeetsTheTargetWithTheStatedProbabilityInsideTheMeanRulesSet) {
  const sa::GridMap g = sa::evaluate_grid(fitted(), box, {"vs", "rq"});
  ASSERT_GT(g.prediction.std.size(), 0);
  const sa::Optimum mean = sa::find_optimum(g, 0, 1, target, {0.5});
  const sa::Optimum sure = sa::find_optimum(g, 0, 1, target, {0.9});
  ASSERT_TRUE(mean.found);
  ASSERT_TRUE(sure.found);
  EXPECT_EQ(sure.confidence, 0.9);
  EXPECT_EQ(sure.std_source, "model");
  const double s = g.prediction.std(Eigen::Index(sure.row), 1);
  EXPECT_GT(s, 0.0);
  EXPECT_EQ(sure.rq_std, s);
  EXPECT_GE(probability(sure.rq, s, target), 0.9);
  EXPECT_EQ(sure.probability, probability(sure.rq, s, target));
  EXPECT_LE(sure.rq, target);    // inside the mean rule's feasible set
  EXPECT_LE(sure.vs, mean.vs);   // so never more V_s than the mean rule's point
  EXPECT_LT(mean.probability, 0.9) << "the mean rule's point is the coin toss the confidence guards against";
  // the most V_s among every point that meets the confidence: none better is left out
  for (Eigen::Index r = 0; r < g.x.rows(); ++r)
    if (probability(g.prediction.mean(r, 1), g.prediction.std(r, 1), target) >= 0.9 + 1e-9) {
      EXPECT_LE(g.prediction.mean(r, 0), sure.vs) << "grid row " << r;
    }
}

TEST(ConfidentOptimum, ConfidenceOneHalfIsTheMeanRuleBitForBit) {
  const sa::GridMap g = sa::evaluate_grid(fitted(), box, {"vs", "rq"});
  // the mean rule as it always was: the largest V_s whose predicted R_q is at most the target
  Eigen::Index best = -1;
  for (Eigen::Index r = 0; r < g.x.rows(); ++r)
    if (g.prediction.mean(r, 1) <= target && (best < 0 || g.prediction.mean(r, 0) > g.prediction.mean(best, 0)))
      best = r;
  ASSERT_GE(best, 0);
  const sa::Optimum o = sa::find_optimum(g, 0, 1, target, {0.5});
  EXPECT_EQ(Eigen::Index(o.row), best);
  EXPECT_EQ(o.vs, g.prediction.mean(best, 0));
  EXPECT_EQ(o.rq, g.prediction.mean(best, 1));
  EXPECT_EQ(o.x, g.x.row(best).transpose());
}
