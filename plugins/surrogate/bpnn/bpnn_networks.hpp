// The bpnn plugin's model: one network for all outputs (the study's, the default) or one per output.
//
// Why one per output can matter: a shared hidden layer couples the outputs' fits. Where one output is
// much noisier than another (on the study's layout R_q's heap-to-heap scatter is a large share of its
// spread, V_s's a few per cent), the shared features also follow the noisy output, and early
// stopping picks one epoch for all, the one at which the noisy output starts to learn its noise.
// Separate networks give each output its own fit and its own stopping epoch (docs/surrogates.md).
#pragma once
#include <Eigen/Dense>
#include <nlohmann/json.hpp>

#include <vector>

#include "bpnn_model.hpp"

namespace spreadmap::surrogate {

class BpnnNetworks {
 public:
  BpnnNetworks(BpnnConfig config = {}, bool per_output = false) : config_(config), per_output_(per_output) {}

  void fit(const Eigen::MatrixXd &x, const Eigen::MatrixXd &y);
  Eigen::MatrixXd predict(const Eigen::MatrixXd &x) const;
  bool fitted() const { return !nets_.empty(); }
  int n_inputs() const { return fitted() ? nets_.front().n_inputs() : 0; }

  // Shared: the single network's state (as before per-output networks existed); per output:
  // {"networks": [state of output 0, state of output 1, ...]}. from_json reads both.
  nlohmann::json to_json() const;
  static BpnnNetworks from_json(const nlohmann::json &j, BpnnConfig config);
  // One network: its fit info; per output: {"per_output": [fit info of each output's network]}.
  nlohmann::json fit_info() const;
  const BpnnConfig &config() const { return config_; }
  bool per_output() const { return per_output_; }

 private:
  BpnnConfig config_;
  bool per_output_;
  std::vector<BpnnModel> nets_;  // one per output, or one for all
};

}  // namespace spreadmap::surrogate
