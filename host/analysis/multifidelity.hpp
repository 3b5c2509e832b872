// Multi-fidelity adaptive design: most cases at a cheap fidelity (a narrow strip, a coarse preset),
// a few at the expensive one, one model over both. The model sees the fidelity as one more input
// (0 = cheap, 1 = expensive; with ARD the GP learns from its length scale how far the two agree),
// and the map is its prediction at fidelity 1.
//
// After each case the model is refitted; the next setting is the candidate where the expensive
// prediction is least sure (predictive std normalised per output by the range of the expensive
// values, the largest over outputs). There the cheap fidelity runs while the cheap prediction is
// still about as unsure (its std at least `cheap_share` of the expensive one: the shared trend is
// what is missing), the expensive one once the cheap has answered (what is left is the difference
// between the fidelities). The design stops when the leave-one-out NRMSE of the expensive cases
// (each left out of a fit on all the others, cheap ones included) is at most the target for
// `confirm` consecutive fits, or when both budgets are spent.
#pragma once
#include <Eigen/Dense>

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "model.hpp"

namespace spreadmap::analysis {

// The model input that holds the fidelity (0 cheap, 1 expensive); a map holds it at 1.
inline constexpr const char *fidelity_input = "fidelity";

struct MultiFidelityOptions {
  std::size_t budget_cheap = 45, budget_expensive = 15;  // most cases of each fidelity (initial ones included)
  double target_loo_nrmse = 1.0;                         // [%] on the expensive cases, every output...
  std::size_t confirm = 3;                               // ...at this many consecutive fits
  double cheap_share = 0.5;                    // run cheap while its std is at least this share of the expensive one
  std::vector<std::size_t> initial_cheap;      // empty: the 3^d lattice snapped (space_filling_start)
  std::vector<std::size_t> initial_expensive;  // empty: the lattice's corners and centre
};

struct MultiFidelityStep {
  std::size_t cheap = 0, expensive = 0;  // cases fitted at this step
  std::vector<double> loo_nrmse;         // [%] per output, over the expensive cases
};

struct MultiFidelityResult {
  Eigen::MatrixXd x;                // the cases run, in order: the candidate's inputs, then the fidelity (0 or 1)
  Eigen::MatrixXd y;                // their outputs
  std::vector<std::size_t> chosen;  // their candidate rows, in order
  std::vector<MultiFidelityStep> history;
  std::size_t cheap = 0, expensive = 0;
  bool reached_target = false;
  std::string stop_reason;  // "target" | "budget" | "candidates exhausted"
};

// The rows of `start` (candidate rows, e.g. space_filling_start's) at the corners and the centre of
// the candidates' bounding box: the expensive start.
std::vector<std::size_t> corners_and_centre(const Eigen::MatrixXd &candidates, const std::vector<std::size_t> &start);

// candidates: the allowed settings (rows x inputs). make_model: a fresh unfitted model with a
// standard deviation and a closed-form leave-one-out (surrogate/gp). evaluate(x, expensive): runs
// one case at that fidelity and returns its outputs.
MultiFidelityResult multi_fidelity_design(
    const Eigen::MatrixXd &candidates, const std::function<std::unique_ptr<Model>()> &make_model,
    const std::function<Eigen::VectorXd(const Eigen::VectorXd &, bool expensive)> &evaluate,
    const MultiFidelityOptions &options = {});

}  // namespace spreadmap::analysis
