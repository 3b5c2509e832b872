// surrogate/gp core: likelihood (and posterior) gradient against finite differences, interpolation
// with the noise at its lower bound, closed-form leave-one-out against an explicit refit, predictive
// std, and the noise level learned from a noisy set (one level, or one per value of a grouping input).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "plugins/surrogate/gp/gp_model.hpp"
#include "tests/unit/surrogate_study_function.hpp"

namespace sm = spreadmap;
using sm::surrogate::GpConfig;
using sm::surrogate::GpModel;
using sm::surrogate::Kernel;

TEST(SurrogateGp, LikelihoodGradientEqualsFiniteDifferences) {
  const Eigen::MatrixXd x = sm::test::study_grid(4, 5);
  const Eigen::MatrixXd xs =
      (x.rowwise() - x.colwise().mean()).array().rowwise() / Eigen::RowVector2d(0.02, 13).array();
  const Eigen::VectorXd y = sm::test::study_outputs(x).col(1);
  const Eigen::VectorXd ys = (y.array() - y.mean()) / 5e-6;
  for (auto k : {Kernel::squared_exponential, Kernel::matern52}) {
    GpConfig c;
    c.kernel = k;
    const GpModel m(c);
    Eigen::VectorXd theta(4);
    theta << 0.3, -0.2, 0.4, std::log(1e-2);
    Eigen::VectorXd g, gp;
    m.negative_log_likelihood(theta, xs, ys, &g);
    m.negative_log_posterior(theta, xs, ys, &gp);
    for (Eigen::Index i = 0; i < theta.size(); ++i) {
      Eigen::VectorXd a = theta, b = theta;
      a[i] += 1e-5, b[i] -= 1e-5;
      const double fd =
          (m.negative_log_likelihood(a, xs, ys, nullptr) - m.negative_log_likelihood(b, xs, ys, nullptr)) / 2e-5;
      EXPECT_NEAR(g[i], fd, 1e-6 * g.norm()) << sm::surrogate::name_of(k) << " theta " << i;
      const double fd_post =
          (m.negative_log_posterior(a, xs, ys, nullptr) - m.negative_log_posterior(b, xs, ys, nullptr)) / 2e-5;
      EXPECT_NEAR(gp[i], fd_post, 1e-6 * gp.norm()) << sm::surrogate::name_of(k) << " theta " << i << " (posterior)";
    }
    // theta's noise sits at the prior's median (1e-2), where the prior is flat: off it, it pulls back
    Eigen::VectorXd off = theta, g_off, gp_off;
    off[3] = std::log(1e-4);
    m.negative_log_likelihood(off, xs, ys, &g_off);
    m.negative_log_posterior(off, xs, ys, &gp_off);
    EXPECT_NEAR(gp_off[3] - g_off[3], std::log(1e-4 / 1e-2) / 9.0, 1e-12) << "d/dlog n^2 of (log n^2 - log m)^2 / 2w^2";
  }
}

TEST(SurrogateGp, InterpolatesTrainingPointsWithNoiseAtLowerBound) {
  const Eigen::MatrixXd x = sm::test::study_grid(), y = sm::test::study_outputs(x);
  for (auto k : {Kernel::squared_exponential, Kernel::matern52}) {
    GpConfig c;
    c.kernel = k;
    c.noise_max = c.noise_min;  // pinned at the lower bound (1e-12 of each output's variance)
    GpModel m(c);
    m.fit(x, y);
    Eigen::MatrixXd sd;
    const Eigen::MatrixXd p = m.predict(x, &sd);
    // Mean at a training point = y - n^2 alpha: with n^2 = 1e-12 this is ~1e-7 of y here.
    EXPECT_LE(((p - y).array() / y.array()).abs().maxCoeff(), 1e-6) << sm::surrogate::name_of(k);
    for (Eigen::Index c2 = 0; c2 < 2; ++c2)
      EXPECT_LE(sd.col(c2).maxCoeff(), 1e-4 * (y.col(c2).maxCoeff() - y.col(c2).minCoeff()));
    EXPECT_TRUE(m.info()["outputs"][0]["noise_at_lower_bound"].get<bool>());
  }
}

TEST(SurrogateGp, ClosedFormLeaveOneOutEqualsExplicitRefit) {
  const Eigen::MatrixXd x = sm::test::study_grid(3, 4), y = sm::test::study_outputs(x);
  GpConfig c;
  c.noise_min = 1e-6;  // well conditioned, so both routes agree to ~1e-9
  GpModel m(c);
  m.fit(x, y);
  const Eigen::MatrixXd loo = m.loo_mean();
  const nlohmann::json state = m.to_json();
  for (Eigen::Index i = 0; i < x.rows(); ++i) {
    nlohmann::json s = state;  // same hyperparameters and scaling, row i removed
    s["x"].erase(std::size_t(i)), s["y"].erase(std::size_t(i));
    const GpModel without = GpModel::from_json(s, c);
    const Eigen::MatrixXd p = without.predict(x.row(i));
    for (Eigen::Index k = 0; k < 2; ++k)
      EXPECT_NEAR(loo(i, k), p(0, k), 1e-7 * (y.col(k).maxCoeff() - y.col(k).minCoeff())) << "row " << i;
  }
}

TEST(SurrogateGp, StdGrowsAwayFromData) {
  // Noiseless data and the plain marginal likelihood (no noise prior): the noise falls towards its
  // lower bound and the latent std nearly vanishes at the data. (The default prior keeps a noise of
  // about a tenth of the output's spread, which the latent std at a data point then reflects.)
  const Eigen::MatrixXd x = sm::test::study_grid(3, 3), y = sm::test::study_outputs(x);
  GpConfig c;
  c.noise_prior_width = 0;
  GpModel m(c);
  m.fit(x, y);
  Eigen::MatrixXd q(2, 2);
  q << 0.07, 0.0,   // a training point
      0.055, 10.0;  // between four of them
  Eigen::MatrixXd sd;
  m.predict(q, &sd);
  EXPECT_LT(sd(0, 1) * 100, sd(1, 1));
  const GpModel loaded = GpModel::from_json(nlohmann::json::parse(m.to_json().dump()), c);
  Eigen::MatrixXd sd2;
  EXPECT_TRUE((loaded.predict(q, &sd2).array() == m.predict(q).array()).all());
  EXPECT_TRUE((sd2.array() == sd.array()).all());
}

TEST(SurrogateGp, LearnsTheNoiseOfANoisySet) {
  const double sigma = 2e-6;  // [m] 2 um on R_q ~ 100 um, the heap-to-heap scatter
  for (auto k : {Kernel::squared_exponential, Kernel::matern52}) {
    const sm::test::NoisySet s = sm::test::noisy_rq(40, sigma, 7);
    GpConfig c;
    c.kernel = k;
    GpModel m(c);
    m.fit(s.x, s.y);
    const double learned = m.info()["outputs"][0]["noise_std"].get<double>();
    const Eigen::MatrixXd p = m.predict(s.x);
    const double range = s.y.maxCoeff() - s.y.minCoeff();
    const double train_nrmse = 100 * std::sqrt((p - s.y).squaredNorm() / 40) / range;
    const double truth_rmse = std::sqrt((p - s.truth).squaredNorm() / 40);
    std::printf(
        "%s: learned noise %.3f um (true %.3f um), train NRMSE %.2f %% (noise alone: %.2f %%), "
        "RMSE against the noiseless function %.3f um\n",
        sm::surrogate::name_of(k), learned * 1e6, sigma * 1e6, train_nrmse, 100 * sigma / range, truth_rmse * 1e6);
    EXPECT_NEAR(learned, sigma, 0.3 * sigma) << sm::surrogate::name_of(k);
    EXPECT_GT(train_nrmse, 0.5 * 100 * sigma / range) << "the GP still interpolates the noise";
    EXPECT_LT(truth_rmse, sigma) << "the fit should sit closer to the function than the data do";
  }
}

TEST(SurrogateGp, KnownNoiseShrinksThePosteriorMeanAsItsClosedFormSays) {
  // Two points far apart for the length scale (independent: k(x1, x2) = exp(-0.5e6) = 0), unit
  // scaling, signal k = s^2 and nugget n^2 fixed by the state: at each point the posterior mean is
  // k / (k + n^2 + sigma_i^2) y_i, so the point measured with the larger scatter is followed less.
  const double s2 = 2.0, n2 = 1e-3, var_small = 0.01, var_large = 3.0, y1 = 1.5, y2 = -1.5;
  const nlohmann::json state = {{"kernel", "squared_exponential"},
                                {"x_scale", {{"mean", {0.0}}, {"scale", {1.0}}}},
                                {"y_scale", {{"mean", {0.0}}, {"scale", {1.0}}}},
                                {"x", {{0.0}, {1.0}}},
                                {"y", {{y1}, {y2}}},
                                {"noise_var", {{var_small}, {var_large}}},
                                {"theta", {{std::log(s2), std::log(1e-3), std::log(n2)}}}};
  const GpModel m = GpModel::from_json(state, {});
  Eigen::MatrixXd x(2, 1);
  x << 0.0, 1.0;
  const Eigen::MatrixXd p = m.predict(x);
  EXPECT_NEAR(p(0, 0), s2 / (s2 + n2 + var_small) * y1, 1e-12);
  EXPECT_NEAR(p(1, 0), s2 / (s2 + n2 + var_large) * y2, 1e-12);
  EXPECT_GT(std::abs(p(1, 0) - y2), 10 * std::abs(p(0, 0) - y1)) << "the scattered point is followed less tightly";
  // saved and loaded again, the known noise stays part of the model
  const GpModel again = GpModel::from_json(m.to_json(), {});
  EXPECT_EQ(again.predict(x), p);
}

TEST(SurrogateGp, AFittedPointWithALargeKnownScatterIsFollowedLessTightly) {
  // A smooth response on a 5 x 5 grid with one point pushed off it: given a large known variance
  // there, the fitted mean stays nearer the smooth response than when that point is said to be precise.
  // The learnt nugget is pinned at its lower bound: only the known noise tells the points apart.
  const Eigen::MatrixXd x = sm::test::study_grid(5, 5);
  Eigen::MatrixXd y = sm::test::study_outputs(x).col(0);
  const Eigen::Index odd = 12;  // the centre
  const double range = y.maxCoeff() - y.minCoeff(), kick = 0.2 * range;
  const double smooth = y(odd, 0);
  y(odd, 0) += kick;
  Eigen::MatrixXd precise = Eigen::MatrixXd::Constant(y.rows(), 1, std::pow(1e-3 * range, 2));
  Eigen::MatrixXd scattered = precise;
  scattered(odd, 0) = std::pow(0.5 * range, 2);
  GpConfig pinned;
  pinned.noise_max = pinned.noise_min;
  GpModel a(pinned), b(pinned);
  a.fit(x, y, precise);
  b.fit(x, y, scattered);
  const double miss_precise = std::abs(a.predict(x.row(odd))(0, 0) - y(odd, 0));
  const double miss_scattered = std::abs(b.predict(x.row(odd))(0, 0) - y(odd, 0));
  EXPECT_GT(miss_scattered, 2 * miss_precise);
  EXPECT_LT(std::abs(b.predict(x.row(odd))(0, 0) - smooth), 0.5 * kick) << "nearer the smooth response than the kick";
  EXPECT_THROW(a.fit(x, y, Eigen::MatrixXd::Constant(y.rows(), 1, -1.0)), std::invalid_argument);
}

TEST(SurrogateGp, GroupedNoiseGradientEqualsFiniteDifferences) {
  // Two nuggets (rows alternately in groups 0 and 1): each one's derivative, with and without the prior
  const Eigen::MatrixXd x = sm::test::study_grid(4, 5);
  const Eigen::MatrixXd xs =
      (x.rowwise() - x.colwise().mean()).array().rowwise() / Eigen::RowVector2d(0.02, 13).array();
  const Eigen::VectorXd y = sm::test::study_outputs(x).col(1);
  const Eigen::VectorXd ys = (y.array() - y.mean()) / 5e-6;
  std::vector<int> group(std::size_t(x.rows()));
  for (std::size_t i = 0; i < group.size(); ++i) group[i] = int(i % 2);
  const GpModel m;
  Eigen::VectorXd theta(5);
  theta << 0.3, -0.2, 0.4, std::log(3e-2), std::log(2e-3);
  Eigen::VectorXd g, gp;
  m.negative_log_likelihood(theta, xs, ys, &g, nullptr, &group);
  m.negative_log_posterior(theta, xs, ys, &gp, nullptr, &group);
  for (Eigen::Index i = 0; i < theta.size(); ++i) {
    Eigen::VectorXd a = theta, b = theta;
    a[i] += 1e-5, b[i] -= 1e-5;
    const double fd = (m.negative_log_likelihood(a, xs, ys, nullptr, nullptr, &group) -
                       m.negative_log_likelihood(b, xs, ys, nullptr, nullptr, &group)) /
                      2e-5;
    EXPECT_NEAR(g[i], fd, 1e-6 * g.norm()) << "theta " << i;
    const double fd_post = (m.negative_log_posterior(a, xs, ys, nullptr, nullptr, &group) -
                            m.negative_log_posterior(b, xs, ys, nullptr, nullptr, &group)) /
                           2e-5;
    EXPECT_NEAR(gp[i], fd_post, 1e-6 * gp.norm()) << "theta " << i << " (posterior)";
  }
  // equal nuggets are one nugget
  Eigen::VectorXd same = theta, one(4);
  same[4] = same[3];
  one << theta.head(4);
  EXPECT_NEAR(m.negative_log_likelihood(same, xs, ys, nullptr, nullptr, &group),
              m.negative_log_likelihood(one, xs, ys, nullptr), 1e-9);
}

TEST(SurrogateGp, LearnsANoiseLevelPerValueOfTheGroupingInput) {
  // A two-fidelity set: the same function (R_q-like), 60 cheap rows (fidelity 0) scattered by 3 um
  // and 30 expensive ones (fidelity 1) by 1 um. One noise per fidelity finds both within 30 %; one
  // shared noise sits between them and overstates the expensive rows' scatter.
  const double sigma_cheap = 3e-6, sigma_expensive = 1e-6;
  const sm::test::NoisySet cheap = sm::test::noisy_rq(60, sigma_cheap, 11);
  const sm::test::NoisySet expensive = sm::test::noisy_rq(30, sigma_expensive, 12);
  Eigen::MatrixXd x(90, 3), y(90, 1), truth(90, 1);
  x << cheap.x, Eigen::VectorXd::Zero(60), expensive.x, Eigen::VectorXd::Ones(30);
  y << cheap.y, expensive.y;
  truth << cheap.truth, expensive.truth;
  GpConfig grouped;
  grouped.noise_group_input = 2;
  GpModel m(grouped), shared;
  m.fit(x, y);
  shared.fit(x, y);
  const auto info = m.info()["outputs"][0];
  const double learned_cheap = info["noise_std_by_group"][0]["noise_std"].get<double>();
  const double learned_expensive = info["noise_std_by_group"][1]["noise_std"].get<double>();
  const double learned_shared = shared.info()["outputs"][0]["noise_std"].get<double>();
  std::printf("learned noise: cheap %.3f um (true %.3f), expensive %.3f um (true %.3f); one shared %.3f um\n",
              learned_cheap * 1e6, sigma_cheap * 1e6, learned_expensive * 1e6, sigma_expensive * 1e6,
              learned_shared * 1e6);
  EXPECT_EQ(info["noise_std"].get<double>(), learned_expensive) << "noise_std is the largest value's group";
  EXPECT_NEAR(learned_cheap, sigma_cheap, 0.3 * sigma_cheap);
  EXPECT_NEAR(learned_expensive, sigma_expensive, 0.3 * sigma_expensive);
  EXPECT_GT(learned_shared, 1.5 * sigma_expensive) << "one shared noise overstates the expensive rows' scatter";

  // saved and loaded again, the groups stay part of the model
  const GpModel again = GpModel::from_json(nlohmann::json::parse(m.to_json().dump()), {});
  EXPECT_TRUE((again.predict(x).array() == m.predict(x).array()).all());
  EXPECT_EQ(again.info()["outputs"][0]["noise_std"].get<double>(), learned_expensive);

  // refused with a message naming what is wrong: grouping by a setting (90 distinct values), an
  // input past the last one (named as the user writes it)
  const auto refusal = [&](int input) {
    GpConfig c;
    c.noise_group_input = input;
    GpModel model(c);
    try {
      model.fit(x, y);
    } catch (const std::invalid_argument &e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_NE(refusal(0).find("input 1 takes 90 values"), std::string::npos) << refusal(0);
  EXPECT_NE(refusal(3).find("noise_by_input = 4 is past the 3 inputs"), std::string::npos) << refusal(3);
}
