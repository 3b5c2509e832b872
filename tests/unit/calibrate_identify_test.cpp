// The inverse step of calibration: parameters from measured angles.
// A linear angle model has a closed-form identified set: with J the angles' derivatives in the
// parameters and S = diag(sigma^2), the set chi2 <= chi2_min + 2.30 is an ellipse whose extent along
// parameter k is +- sqrt(2.30 C_kk), C = (J^T S^-1 J)^-1. The grid resolves it to one step.
#include <gtest/gtest.h>

#include <cmath>

#include "analysis/plugin_model.hpp"
#include "core/schema.hpp"
#include "unit/built_plugins.hpp"
#include "workflow/calibrate/identify.hpp"

namespace {

namespace cal = spreadmap::calibrate;

// Repose-like and drum-like angles [deg], linear in friction mu and rolling friction mu_r.
Eigen::MatrixXd linear_angles(const Eigen::MatrixXd &p) {
  Eigen::MatrixXd a(p.rows(), 2);
  for (Eigen::Index i = 0; i < p.rows(); ++i) {
    a(i, 0) = 20 + 25 * p(i, 0) + 30 * p(i, 1);
    a(i, 1) = 25 + 15 * p(i, 0) + 60 * p(i, 1);
  }
  return a;
}

const std::vector<cal::ParameterRange> box = {{"friction", 0.1, 0.9}, {"rolling_friction", 0.0, 0.4}};

TEST(CalibrateIdentify, LinearAnglesGiveTheClosedFormEllipse) {
  const double mu = 0.45, mu_r = 0.12, sigma = 1.0;
  Eigen::MatrixXd truth(1, 2);
  truth << mu, mu_r;
  const Eigen::MatrixXd angles = linear_angles(truth);
  const std::vector<cal::MeasuredAngle> measured = {{"repose", angles(0, 0), sigma}, {"drum", angles(0, 1), sigma}};
  const auto id = cal::identify(
      box, measured,
      [](const Eigen::MatrixXd &p) {
        return spreadmap::analysis::Prediction{linear_angles(p), {}};
      },
      401);
  const double step_mu = 0.8 / 400, step_r = 0.4 / 400;
  EXPECT_NEAR(id.best[0], mu, step_mu);
  EXPECT_NEAR(id.best[1], mu_r, step_r);
  EXPECT_NEAR(id.chi2_min, 0, 1e-3);
  Eigen::Matrix2d j;
  j << 25, 30, 15, 60;
  const Eigen::Matrix2d c = (j.transpose() * j / (sigma * sigma)).inverse();
  const double half_mu = std::sqrt(2.30 * c(0, 0)), half_r = std::sqrt(2.30 * c(1, 1));
  EXPECT_NEAR(id.lower[0], mu - half_mu, 1.5 * step_mu);
  EXPECT_NEAR(id.upper[0], mu + half_mu, 1.5 * step_mu);
  EXPECT_NEAR(id.lower[1], mu_r - half_r, 1.5 * step_r);
  EXPECT_NEAR(id.upper[1], mu_r + half_r, 1.5 * step_r);
  EXPECT_FALSE(id.open_at_lo[0] || id.open_at_hi[0] || id.open_at_lo[1] || id.open_at_hi[1]);
}

TEST(CalibrateIdentify, OneAngleCannotPinTwoParameters) {
  const std::vector<cal::MeasuredAngle> measured = {{"repose", 20 + 25 * 0.45 + 30 * 0.12, 1.0}};
  const auto id = cal::identify(box, measured, [](const Eigen::MatrixXd &p) {
    return spreadmap::analysis::Prediction{linear_angles(p).leftCols(1), {}};
  });
  // A valley across the box: friction anywhere from where rolling friction is 0.4 to where it is 0.
  EXPECT_TRUE(id.open_at_lo[1] && id.open_at_hi[1]);
  EXPECT_GT(id.upper[0] - id.lower[0], 0.4);
}

// The surrogate the calibration uses (the gp plugin) fitted on a 4 x 4 design of a mildly nonlinear
// truth: the measured angles of a parameter pair between the design points identify it, inside the
// reported set.
TEST(CalibrateIdentify, GaussianProcessOnAFewRunsRecoversTheParameters) {
  auto truth = [](const Eigen::MatrixXd &p) {
    Eigen::MatrixXd a = linear_angles(p);
    for (Eigen::Index i = 0; i < p.rows(); ++i) a(i, 0) -= 8 * p(i, 0) * p(i, 0);  // saturation in mu
    return a;
  };
  Eigen::MatrixXd design(16, 2);
  for (int i = 0; i < 4; ++i)
    for (int k = 0; k < 4; ++k) design.row(i * 4 + k) << 0.1 + 0.8 * i / 3.0, 0.4 * k / 3.0;
  const auto &gp = built_plugins().get("surrogate", "gp");
  auto model = spreadmap::analysis::PluginModel::create(gp.descriptor,
                                                        spreadmap::default_params(*gp.descriptor, gp.id()).dump());
  model->fit(design, truth(design));
  Eigen::MatrixXd p(1, 2);
  p << 0.55, 0.21;
  const Eigen::MatrixXd angles = truth(p);
  const std::vector<cal::MeasuredAngle> measured = {{"repose", angles(0, 0), 0.5}, {"drum", angles(0, 1), 0.5}};
  const auto id = cal::identify(box, measured, [&](const Eigen::MatrixXd &q) { return model->predict(q); });
  EXPECT_LE(id.lower[0], 0.55);
  EXPECT_GE(id.upper[0], 0.55);
  EXPECT_LE(id.lower[1], 0.21);
  EXPECT_GE(id.upper[1], 0.21);
  EXPECT_NEAR(id.best[0], 0.55, 0.05);
  EXPECT_NEAR(id.best[1], 0.21, 0.03);
}

}  // namespace
