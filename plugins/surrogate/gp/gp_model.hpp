// Gaussian-process regression (Rasmussen & Williams 2006, ch. 2 and 5), one independent GP per
// output, on standardised inputs and outputs.
//
// Kernels (ARD: one length scale l_d per input; r^2 = sum_d (x_d - x'_d)^2 / l_d^2):
//   squared_exponential  k = s^2 exp(-r^2 / 2)
//   matern52             k = s^2 (1 + sqrt5 r + 5 r^2 / 3) exp(-sqrt5 r)
// plus a noise variance n^2 on the diagonal (the nugget: the scatter of repeated runs). With
// noise_group_input the rows are grouped by that input's value (a fidelity: 0 cheap, 1 expensive) and
// each group has its own nugget n_g^2: a narrow cheap strip scatters more than the full-width runs, and
// one shared nugget would blur the expensive ones. Hyperparameters theta = log(s^2, l_1..l_d, n_1^2..n_G^2)
// (G = 1 without groups) maximise the log marginal likelihood plus a log-normal prior on n^2
// each (median 1e-2 of the output's variance, log-sd 3: weak, yet on a handful of noisy points it keeps
// the likelihood's flat valley from sliding to interpolation), by analytic gradient and bounded
// L-BFGS from `restarts` starts: the first at s = l = 1, the others drawn from a seeded generator;
// the best wins. noise_prior_width = 0 gives the plain marginal likelihood (scikit-learn's).
// Per-row noise known beforehand (fit's noise_var: the scatter^2 / count of replicated runs) is added
// to the diagonal on top of the learnt nugget, so a point measured less precisely is followed less
// tightly (heteroscedastic noise). Predictions: the posterior mean and the standard deviation of the
// latent function (without the noise). Leave-one-out predictions come in closed form, mu_-i = y_i - alpha_i / [K^-1]_ii
// (R&W 5.12).
#pragma once
#include <Eigen/Dense>
#include <nlohmann/json.hpp>

#include <cstdint>
#include <string>
#include <vector>

#include "../common/standardiser.hpp"

namespace spreadmap::surrogate {

enum class Kernel { squared_exponential, matern52 };
Kernel kernel_from_name(const std::string &name);
const char *name_of(Kernel k);

struct GpConfig {
  Kernel kernel = Kernel::squared_exponential;
  int restarts = 5;  // optimiser starts (>= 1)
  std::uint64_t seed = 1;
  double noise_min = 1e-12;   // lower bound of n^2, as a share of each output's variance
  double noise_max = 1.0;     // upper bound of n^2, same scale
  long max_iterations = 300;  // L-BFGS iterations per start
  // Log-normal prior on n^2 (share of each output's variance): log n^2 ~ N(log median, width^2);
  // width 0 = none (plain marginal likelihood).
  double noise_prior_median = 1e-2, noise_prior_width = 3.0;
  // The input (0-based column) whose distinct values each get their own nugget; -1: one for all rows.
  int noise_group_input = -1;
};

inline constexpr int max_noise_groups = 8;

class GpModel {
 public:
  explicit GpModel(GpConfig config = {}) : config_(config) {}

  // noise_var: rows x outputs of known variances in the outputs' units squared (0: none), or empty.
  void fit(const Eigen::MatrixXd &x, const Eigen::MatrixXd &y, const Eigen::MatrixXd &noise_var = {});
  // Posterior mean (rows x outputs); the latent standard deviation into *std when not null.
  Eigen::MatrixXd predict(const Eigen::MatrixXd &x, Eigen::MatrixXd *std = nullptr) const;
  // Closed-form leave-one-out predictions at the training rows (raw units).
  Eigen::MatrixXd loo_mean() const;
  bool fitted() const { return !outputs_.empty(); }
  int n_inputs() const { return int(x_train_.cols()); }

  // -log marginal likelihood of standardised data at log-hyperparameters theta, with gradient.
  // Returns +inf when K is not positive definite. Public for the gradient test. `known`: per-row
  // variances (standardised) added to the diagonal, or null. `group`: each row's noise group (its
  // nugget theta[d + 1 + g]), or null: one nugget, theta[d + 1].
  double negative_log_likelihood(const Eigen::VectorXd &theta, const Eigen::MatrixXd &xs, const Eigen::VectorXd &ys,
                                 Eigen::VectorXd *grad, const Eigen::VectorXd *known = nullptr,
                                 const std::vector<int> *group = nullptr) const;

  // The same plus the noise prior's -log density (up to a constant): what the fit minimises.
  double negative_log_posterior(const Eigen::VectorXd &theta, const Eigen::MatrixXd &xs, const Eigen::VectorXd &ys,
                                Eigen::VectorXd *grad, const Eigen::VectorXd *known = nullptr,
                                const std::vector<int> *group = nullptr) const;

  nlohmann::json to_json() const;  // state: kernel, scaling, training data, theta per output
  static GpModel from_json(const nlohmann::json &j, GpConfig config);
  nlohmann::json info() const;  // hyperparameters in input/output units, lml, LOO predictions
  const GpConfig &config() const { return config_; }

 private:
  struct Output {
    Eigen::VectorXd theta;  // log(s^2), log(l_1..d), log(n_1^2..n_G^2)
    double lml = 0;         // log marginal likelihood (standardised data)
    Eigen::MatrixXd chol;   // lower Cholesky factor of K + n^2 I
    Eigen::VectorXd alpha;  // (K + n^2 I)^-1 y
    Eigen::VectorXd loo;    // leave-one-out means, standardised
    long iterations = 0;
  };
  Eigen::MatrixXd kernel(const Eigen::VectorXd &theta, const Eigen::MatrixXd &a, const Eigen::MatrixXd &b) const;
  void prepare(Output &out, const Eigen::VectorXd &ys, const Eigen::VectorXd *known) const;  // chol, alpha, lml, loo
  // Output c's known variances on the standardised scale, or null when none were given.
  const Eigen::VectorXd *known_noise(std::size_t c) const;
  void set_known_noise(const Eigen::MatrixXd &noise_var);  // after y_scale_ is set
  void set_noise_groups(std::vector<double> values);       // group_ from x_train_ and these values
  int noise_count() const { return group_values_.empty() ? 1 : int(group_values_.size()); }
  const std::vector<int> *groups() const { return group_values_.empty() ? nullptr : &group_; }

  GpConfig config_;
  Standardiser x_scale_, y_scale_;
  Eigen::MatrixXd x_train_, y_train_;   // raw
  Eigen::MatrixXd noise_var_;           // raw, rows x outputs; empty when none was given
  std::vector<Eigen::VectorXd> known_;  // per output: noise_var_ standardised
  Eigen::MatrixXd xs_;                  // standardised inputs
  std::vector<double> group_values_;    // the grouping input's distinct values, ascending; empty: no groups
  std::vector<int> group_;              // per training row: its index in group_values_
  std::vector<Output> outputs_;
};

}  // namespace spreadmap::surrogate
