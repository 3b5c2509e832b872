// surrogate/bpnn core: back-propagated gradient against finite differences, the loss definitions
// at a known point, determinism for a seed, a bitwise save/load round trip, and one network per
// output keeping a noisy output out of a clean one's fit.
#include <gtest/gtest.h>

#include "plugins/surrogate/bpnn/bpnn_model.hpp"
#include "plugins/surrogate/bpnn/bpnn_networks.hpp"
#include "tests/unit/surrogate_study_function.hpp"

namespace sm = spreadmap;
using sm::surrogate::Activation;
using sm::surrogate::BpnnConfig;
using sm::surrogate::BpnnModel;
using sm::surrogate::Regularisation;

namespace {

Eigen::MatrixXd random_matrix(Eigen::Index r, Eigen::Index c, unsigned seed) {
  std::srand(seed);
  return Eigen::MatrixXd::Random(r, c);
}

// Central differences with h = 1e-5 have truncation error ~h^2 |f'''| ~ 1e-10 and round-off
// ~eps |f| / h ~ 1e-11 here, so 1e-6 relative (against the gradient's norm) is a real check.
void expect_gradient_matches(const BpnnConfig &config) {
  BpnnModel m(config);
  m.initialise(3, 2);
  const Eigen::MatrixXd x = random_matrix(11, 3, 1), y = random_matrix(11, 2, 2);
  Eigen::VectorXd p = m.parameters() + 0.3 * random_matrix(m.parameters().size(), 1, 3);
  Eigen::VectorXd g;
  m.loss(p, x, y, &g);
  Eigen::VectorXd fd(p.size());
  const double h = 1e-5;
  for (Eigen::Index i = 0; i < p.size(); ++i) {
    Eigen::VectorXd a = p, b = p;
    a[i] += h, b[i] -= h;
    fd[i] = (m.loss(a, x, y, nullptr) - m.loss(b, x, y, nullptr)) / (2 * h);
  }
  EXPECT_LE((g - fd).norm(), 1e-6 * g.norm()) << "activation " << sm::surrogate::name_of(config.activation)
                                              << ", regularisation " << sm::surrogate::name_of(config.regularisation);
  EXPECT_LE((g - fd).lpNorm<Eigen::Infinity>(), 1e-6 * g.lpNorm<Eigen::Infinity>());
}

}  // namespace

TEST(SurrogateBpnn, BackPropagatedGradientEqualsFiniteDifferences) {
  for (auto a : {Activation::sigmoid, Activation::tanh, Activation::atan})
    for (auto r : {Regularisation::ratio, Regularisation::sum})
      for (int layers : {1, 2}) {
        BpnnConfig c;
        c.activation = a, c.regularisation = r, c.hidden_layers = layers, c.units = 7, c.lambda = 0.1;
        expect_gradient_matches(c);
      }
}

TEST(SurrogateBpnn, LossReadingsAtZeroWeights) {
  // All weights and biases zero: outputs are 0, so mse = mean(y^2) and the penalty vanishes.
  BpnnConfig c;
  c.units = 4, c.lambda = 0.1;
  const Eigen::MatrixXd x = random_matrix(5, 2, 4), y = random_matrix(5, 2, 5);
  const double mse = y.squaredNorm() / 10.0;
  c.regularisation = Regularisation::ratio;
  BpnnModel ratio(c);
  ratio.initialise(2, 2);
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(ratio.parameters().size());
  EXPECT_NEAR(ratio.loss(zero, x, y, nullptr), 0.9 * mse, 1e-15);
  c.regularisation = Regularisation::sum;
  BpnnModel sum(c);
  sum.initialise(2, 2);
  EXPECT_NEAR(sum.loss(zero, x, y, nullptr), y.squaredNorm() / 5.0, 1e-15);  // (1/N) sum ||Y_i - O_i||^2
  // Penalty alone: with y = outputs... use unit weights and check the ratio's mean vs the sum.
  Eigen::VectorXd ones = Eigen::VectorXd::Ones(zero.size());
  const double n_w = 2 * 4 + 4 * 2;  // weights only, biases not penalised
  double mse_ratio = 0, mse_sum = 0;
  const double lr = ratio.loss(ones, x, y, nullptr, &mse_ratio), ls = sum.loss(ones, x, y, nullptr, &mse_sum);
  EXPECT_NEAR(lr, 0.9 * mse_ratio + 0.1 * n_w / n_w, 1e-12);
  EXPECT_NEAR(ls, 2 * mse_sum + 0.1 * n_w, 1e-12);
}

TEST(SurrogateBpnn, SameSeedSameFitAndRoundTripIsBitwise) {
  const Eigen::MatrixXd x = sm::test::study_grid(3, 5), y = sm::test::study_outputs(x);
  BpnnConfig c;
  c.units = 20, c.epochs = 200, c.seed = 42;
  BpnnModel a(c), b(c);
  a.fit(x, y), b.fit(x, y);
  const Eigen::MatrixXd q = sm::test::study_grid(7, 11);
  const Eigen::MatrixXd pa = a.predict(q);
  EXPECT_TRUE((pa.array() == b.predict(q).array()).all());
  c.seed = 43;
  BpnnModel other(c);
  other.fit(x, y);
  EXPECT_FALSE((pa.array() == other.predict(q).array()).all());
  const BpnnModel loaded = BpnnModel::from_json(nlohmann::json::parse(a.to_json().dump()), BpnnConfig{});
  EXPECT_TRUE((pa.array() == loaded.predict(q).array()).all());
}

TEST(SurrogateBpnn, EarlyStoppingKeepsTheBestValidationWeights) {
  const Eigen::MatrixXd x = sm::test::study_grid(), y = sm::test::study_outputs(x);
  BpnnConfig c;
  c.units = 30, c.epochs = 2000, c.validation_share = 0.2, c.patience = 20,
  c.optimiser = sm::surrogate::Optimiser::adam;
  c.learning_rate = 1e-2;
  BpnnModel m(c);
  const auto info = m.fit(x, y);
  EXPECT_GE(info.validation_mse, 0.0);
  EXPECT_LE(info.epochs, 2000);
  EXPECT_LT(info.validation_mse, 0.05);  // standardised outputs: below 5 % of their variance
}

TEST(SurrogateBpnn, StoppingFoldsStopBeforeTheNoiseIsLearnt) {
  // An unregularised network on 40 noisy rows: trained to the end it follows the noise; stopped at
  // the epoch its cross-validation folds agree on, it stays nearer the noiseless function.
  const double sigma = 2e-6;
  const sm::test::NoisySet s = sm::test::noisy_rq(40, sigma, 7);
  BpnnConfig c;
  c.units = 50, c.lambda = 0, c.epochs = 2000, c.patience = 100;
  BpnnModel full(c);
  const auto info_full = full.fit(s.x, s.y);
  c.stopping_folds = 5;
  BpnnModel stopped(c);
  const auto info = stopped.fit(s.x, s.y);
  ASSERT_EQ(info.fold_epochs.size(), 5u);
  double mean = 0;
  for (long e : info.fold_epochs) {
    EXPECT_GE(e, 1);
    EXPECT_LE(e, 2000);
    mean += double(e) / 5;
  }
  EXPECT_LE(info.epochs, std::max(1L, std::lround(mean)));  // all rows, for the folds' mean epoch
  EXPECT_TRUE(info.stopped_early);
  const auto off_truth = [&](const BpnnModel &m) { return std::sqrt((m.predict(s.x) - s.truth).squaredNorm() / 40); };
  std::printf(
      "epochs: to the end %ld, stopped %ld (folds' best: %ld %ld %ld %ld %ld); RMSE against the noiseless "
      "function: %.3f um to the end, %.3f um stopped (noise %.3f um)\n",
      info_full.epochs, info.epochs, info.fold_epochs[0], info.fold_epochs[1], info.fold_epochs[2], info.fold_epochs[3],
      info.fold_epochs[4], off_truth(full) * 1e6, off_truth(stopped) * 1e6, sigma * 1e6);
  EXPECT_LT(info.epochs, info_full.epochs);
  EXPECT_LT(off_truth(stopped), off_truth(full));
}

TEST(SurrogateBpnn, RejectsBadData) {
  BpnnModel m;
  Eigen::MatrixXd x = Eigen::MatrixXd::Zero(3, 2), y = Eigen::MatrixXd::Zero(2, 2);
  EXPECT_THROW(m.fit(x, y), std::invalid_argument);
  y = Eigen::MatrixXd::Zero(3, 2);
  y(1, 1) = std::nan("");
  EXPECT_THROW(m.fit(x, y), std::invalid_argument);
  EXPECT_THROW(m.predict(x), std::logic_error);
}

TEST(SurrogateBpnn, PerOutputNetworksKeepANoisyOutputOutOfACleanOne) {
  // The study's 45 cases, V_s exact beside R_q with 3 um of noise (its spread over the box is ~5 um),
  // 200 units, ratio lambda 0.1, early stopping by 5 cross-validation folds. One network
  // per output: V_s's network never sees R_q, so its prediction is bitwise the same whatever R_q's
  // noise. A shared network stops at the epoch where R_q starts to learn its noise, before V_s is
  // fitted (measured on a 13 x 17 grid: V_s NRMSE 0.31 % per output, 1.61 % shared).
  const Eigen::MatrixXd x = sm::test::study_grid(), truth = sm::test::study_outputs(x);
  sm::Random rng(5);
  Eigen::MatrixXd y = truth, y_other = truth;
  for (Eigen::Index r = 0; r < y.rows(); ++r) y(r, 1) += 3e-6 * rng.normal(), y_other(r, 1) += 3e-6 * rng.normal();
  BpnnConfig c;
  c.stopping_folds = 5;
  sm::surrogate::BpnnNetworks per(c, true), per_other(c, true), shared(c, false);
  per.fit(x, y), per_other.fit(x, y_other), shared.fit(x, y);
  const Eigen::MatrixXd q = sm::test::study_grid(13, 17), q_truth = sm::test::study_outputs(q);
  const Eigen::VectorXd p_per = per.predict(q).col(0), p_shared = shared.predict(q).col(0);
  EXPECT_TRUE((p_per.array() == per_other.predict(q).col(0).array()).all());
  const double range = q_truth.col(0).maxCoeff() - q_truth.col(0).minCoeff();
  const auto error = [&](const Eigen::VectorXd &p) {
    return 100 * std::sqrt((p - q_truth.col(0)).squaredNorm() / double(p.size())) / range;
  };
  std::printf("V_s NRMSE on a 13 x 17 grid: per output %.3f %%, shared %.3f %%\n", error(p_per), error(p_shared));
  EXPECT_LT(error(p_per), 0.5);  // the study's 2.21 % test error, met with a margin
  EXPECT_LT(error(p_per), 0.5 * error(p_shared));
  // The per-output state round-trips bitwise.
  const auto loaded = sm::surrogate::BpnnNetworks::from_json(nlohmann::json::parse(per.to_json().dump()), BpnnConfig{});
  EXPECT_TRUE(loaded.per_output());
  EXPECT_TRUE((per.predict(q).array() == loaded.predict(q).array()).all());
}
