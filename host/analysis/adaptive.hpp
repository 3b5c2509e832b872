// Adaptive design of simulations: start from a small space-filling set, fit a GP after each new
// case, run next the allowed setting where the model is least sure (largest predictive std,
// normalised per output by the range of its observed values, the largest over outputs), and stop
// when the cross-validated error is low enough or the budget is spent.
// The cross-validated error is the leave-one-out NRMSE per output from the model's fit_info()
// "loo_mean" (closed form for surrogate/gp); a model without it cannot drive the design.
// Why `confirm`: on a small lattice LOO can be wildly optimistic (a 3-level axis aliases a ripple or
// any odd function to a straight line), so the initial fit never stops the design and the target
// must hold for several consecutive fits.
#pragma once
#include <Eigen/Dense>

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "model.hpp"

namespace spreadmap::analysis {

struct AdaptiveOptions {
  std::size_t budget = 45;           // most cases to run (initial ones included)
  double target_loo_nrmse = 1.0;     // [%] stop when every output's LOO NRMSE is at most this...
  std::size_t confirm = 3;           // ...at this many consecutive fits after the initial set
  std::vector<std::size_t> initial;  // candidate rows to start with; empty: the 3^d lattice snapped
};

struct AdaptiveStep {
  std::size_t cases = 0;          // cases fitted at this step
  std::vector<double> loo_nrmse;  // [%] per output
};

struct AdaptiveResult {
  Eigen::MatrixXd x, y;               // the cases run, in order
  std::vector<std::size_t> chosen;    // their candidate rows, in order
  std::vector<AdaptiveStep> history;  // one per fit
  bool reached_target = false;
  std::string stop_reason;  // "target" | "budget" | "candidates exhausted"
};

// The 3^d lattice of the candidates' bounding box (corners, edge midpoints, centre), each point
// snapped to its nearest candidate (distances in box-normalised units), duplicates dropped.
std::vector<std::size_t> space_filling_start(const Eigen::MatrixXd &candidates);

// The leave-one-out NRMSE [%] per output over `rows` of y (all rows when empty), from the fitted
// model's fit_info() "loo_mean"; throws std::invalid_argument when the model reports none.
std::vector<double> loo_nrmse_percent(const Model &fitted, const Eigen::MatrixXd &y,
                                      const std::vector<Eigen::Index> &rows = {});

// Whether the stopping target holds: every output's LOO NRMSE of this fit is at most `target` [%],
// and so for `confirm` consecutive fits (the first fit never counts); in_a_row carries the count.
bool target_held(std::size_t &in_a_row, const std::vector<double> &loo_nrmse, double target, std::size_t fits,
                 std::size_t confirm);

// candidates: allowed settings (rows x inputs), e.g. the 5 x 9 design grid or a finer one.
// make_model: a fresh unfitted model (surrogate/gp) each step. evaluate: runs one case, returns its
// outputs (the host connects it to a simulation).
AdaptiveResult adaptive_design(const Eigen::MatrixXd &candidates,
                               const std::function<std::unique_ptr<Model>()> &make_model,
                               const std::function<Eigen::VectorXd(const Eigen::VectorXd &)> &evaluate,
                               const AdaptiveOptions &options = {});

}  // namespace spreadmap::analysis
