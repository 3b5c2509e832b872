// Back-propagation neural network (the reference study's surrogate, Table 3): fully connected
// hidden layers with a sigmoid-type activation, a linear output layer, inputs and outputs
// standardised (zero mean, unit variance) inside the model.
//
// Loss on standardised data, lambda = regularisation strength, W = all weights (not biases):
//   ratio: L = (1 - lambda) * mse + lambda * mean(W^2)       mse = mean over samples and outputs
//          (the "regularisation ratio" of common NN toolboxes; reproduces the study's ~2 %)
//   sum:   L = (1/N) sum_i ||Y_i - O_i||^2 + lambda * ||W||^2  (the study's Eq. 8 read literally)
// Training: full-batch gradient descent (the study: alpha = 1e-4), Adam, or L-BFGS, optional early
// stopping on a held-out validation share or by K-fold cross-validation of the training rows (each
// fold's best epoch on its held-out rows; the final network trains on every row for their mean). Weights start
// Glorot-uniform from a seeded generator, so a fit is deterministic for a seed.
#pragma once
#include <Eigen/Dense>
#include <nlohmann/json.hpp>

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "../common/standardiser.hpp"

namespace spreadmap::surrogate {

enum class Activation { sigmoid, tanh, atan };
enum class Optimiser { gd, adam, lbfgs };
enum class Regularisation { ratio, sum };

Activation activation_from_name(const std::string &name);
Optimiser optimiser_from_name(const std::string &name);
Regularisation regularisation_from_name(const std::string &name);
const char *name_of(Activation a);
const char *name_of(Optimiser o);
const char *name_of(Regularisation r);

struct BpnnConfig {
  int hidden_layers = 1;
  int units = 200;
  Activation activation = Activation::sigmoid;
  Optimiser optimiser = Optimiser::lbfgs;
  Regularisation regularisation = Regularisation::ratio;
  long epochs = 3000;           // iterations of the optimiser (full batch)
  double learning_rate = 1e-4;  // gd and adam only
  double lambda = 0.1;
  double validation_share = 0;  // share of the training rows held out for early stopping
  long patience = 200;          // epochs without validation improvement before stopping
  long stopping_folds = 0;      // >= 2: early stopping by this many cross-validation folds
  std::uint64_t seed = 1;
  double tolerance = 1e-10;  // relative change of the loss that ends lbfgs early
};

struct BpnnFitInfo {
  double loss = 0;             // final training loss (as defined above, standardised units)
  double mse = 0;              // its data part: mean squared error over samples and outputs
  double validation_mse = -1;  // best validation mse, -1 without early stopping
  long epochs = 0;             // epochs (iterations) run
  bool stopped_early = false;
  std::vector<long> fold_epochs;  // stopping folds: each fold's best epoch
  nlohmann::json to_json() const;
};

class BpnnModel {
 public:
  explicit BpnnModel(BpnnConfig config = {}) : config_(config) {}

  // Fits on raw data (rows = samples). Throws std::invalid_argument on bad shapes or non-finite data.
  BpnnFitInfo fit(const Eigen::MatrixXd &x, const Eigen::MatrixXd &y);
  Eigen::MatrixXd predict(const Eigen::MatrixXd &x) const;
  bool fitted() const { return !weights_.empty(); }
  int n_inputs() const { return fitted() ? int(weights_.front().cols()) : 0; }

  // The network's parameters as one vector (per layer: W column-major, then b) and back.
  Eigen::VectorXd parameters() const;
  void set_parameters(const Eigen::VectorXd &p);
  // Sets up an untrained network of the configured shape with seeded Glorot weights.
  void initialise(int n_in, int n_out);
  // Loss on already standardised data (rows = samples) at parameters p, with its back-propagated
  // gradient when grad is not null. Public for the gradient test.
  double loss(const Eigen::VectorXd &p, const Eigen::MatrixXd &xs, const Eigen::MatrixXd &ys, Eigen::VectorXd *grad,
              double *mse_out = nullptr) const;

  nlohmann::json to_json() const;
  static BpnnModel from_json(const nlohmann::json &j, BpnnConfig config);
  const BpnnConfig &config() const { return config_; }
  const BpnnFitInfo &fit_info() const { return info_; }

 private:
  struct Run {
    Eigen::VectorXd p;  // the parameters reached (the best validation ones when validating)
    double validation_mse = std::numeric_limits<double>::infinity();
    long best_epoch = 0, epochs = 0;
    bool stopped_early = false;
  };
  // Trains fresh weights on (xs, ys), standardised, for at most max_epochs; watches (xv, yv) for
  // early stopping when it has rows.
  Run train(const Eigen::MatrixXd &xs, const Eigen::MatrixXd &ys, const Eigen::MatrixXd &xv, const Eigen::MatrixXd &yv,
            long max_epochs);
  Eigen::MatrixXd forward(const Eigen::MatrixXd &xs) const;  // standardised in and out
  long weight_count() const;

  BpnnConfig config_;
  std::vector<Eigen::MatrixXd> weights_;  // layer l: (out x in)
  std::vector<Eigen::VectorXd> biases_;
  Standardiser x_scale_, y_scale_;
  BpnnFitInfo info_;
};

}  // namespace spreadmap::surrogate
