// Checking a proposed operating point by simulation: what the model predicts there for the mean of
// N new runs (with the interval it claims), what N new runs give (their mean and standard
// deviation), and whether that mean falls inside the interval.
//
// The interval is the prediction +- 2 std, std being the uncertainty of the mean of N new runs:
//   a model with a predictive std (the GP): sqrt(latent^2 + noise^2 / N), noise^2 the learnt nugget^2
//   plus the training points' mean replicate scatter^2 (when the runs were replicated);
//   a model without one (the BP-NN): its cross-validated RMSE (nrmse_cv x the output's range).
#pragma once
#include <Eigen/Dense>
#include <nlohmann/json.hpp>

#include <string>
#include <vector>

#include "analysis/model_file.hpp"
#include "core/registry.hpp"

namespace spreadmap {

struct PredictedValue {
  double mean = 0, std = 0;
  std::string basis;  // how std was obtained, in words
};

// The prediction of every output of the model at x for the mean of `runs` new runs. known_var: per
// output, the mean replicate scatter^2 of the training points (0 where none). Throws InputError
// when the model gives neither a std nor a cross-validated error to build an interval from.
std::vector<PredictedValue> predict_for_runs(PluginRegistry &registry, const analysis::ModelFile &model,
                                             const Eigen::VectorXd &x, std::size_t runs,
                                             const std::vector<double> &known_var);

struct MetricCheck {
  std::string name, unit;
  PredictedValue predicted;
  double lower = 0, upper = 0;    // predicted.mean -+ 2 predicted.std
  std::vector<double> simulated;  // one value per run
  double mean = 0, std = 0;       // of simulated; std NaN below 2 runs
  bool inside = false;            // lower <= mean <= upper
  nlohmann::json to_json() const;
};

MetricCheck check_metric(const std::string &name, const std::string &unit, const PredictedValue &predicted,
                         const std::vector<double> &simulated);

// The inputs of x that lie on the border of the model's box (the range it was trained on):
// [{"input": "U", "side": "max"}, ...].
nlohmann::json edges_of(const analysis::ModelFile &model, const Eigen::VectorXd &x);
// What the log and verified.json say of an optimum on the border.
inline const char *edge_note() { return "at the edge of the explored range: widen U or ω"; }

}  // namespace spreadmap
