// The most efficient operating point for a wanted roughness, and the trade-off frontier.
// The study: "the rightmost U-omega pair": the largest V_s among points that meet the roughness
// target. Here over the evaluated grid (so "within one grid cell" of the true optimum), and with a
// stated confidence: a point meets the target when P(R_q <= target) >= confidence under the
// surrogate's normal predictive law, i.e. when mean + z(confidence) x std <= target. Confidence 0.5
// (z = 0) is the mean rule: predicted R_q at most the target.
#pragma once
#include <Eigen/Dense>
#include <nlohmann/json_fwd.hpp>

#include <cstddef>
#include <string>
#include <vector>

#include "grid.hpp"

namespace spreadmap::analysis {

struct OptimumRule {
  double confidence = 0.5;  // wanted P(R_q <= target), in [0.5, 1)
  // Used where the grid holds no predictive std (a model without uncertainty): one spread for every
  // point, e.g. the model's cross-validated RMSE of R_q [m]. < 0: none; then only confidence 0.5 works.
  double fallback_rq_std = -1;
  std::string std_source = "model";  // where the spread comes from, for optimum.json
};

struct Optimum {
  double rq_max = 0;        // the target
  double confidence = 0.5;  // the rule it was chosen by
  bool found = false;       // false when no grid point meets the target
  std::size_t row = 0;      // grid row
  Eigen::VectorXd x;        // its inputs
  double vs = 0, rq = 0;    // predicted
  double rq_std = -1;       // predicted std of R_q, -1 when the model gives none and no fallback is set
  double probability = -1;  // P(R_q <= rq_max) under a normal predictive law, -1 without std
  std::string std_source;   // "model" or the fallback's source; empty without std
  nlohmann::json to_json(const std::vector<std::string> &input_names) const;
};

// The standard normal quantile z(p) (0 < p < 1); exactly 0 at p = 0.5.
double normal_quantile(double p);

// vs, rq: column indices of V_s and R_q among the grid's outputs. Throws std::invalid_argument for a
// confidence outside [0.5, 1) or above 0.5 with no spread (neither the grid's std nor a fallback).
Optimum find_optimum(const GridMap &grid, std::size_t vs, std::size_t rq, double rq_max, const OptimumRule &rule);
std::vector<Optimum> find_optima(const GridMap &grid, std::size_t vs, std::size_t rq,
                                 const std::vector<double> &rq_max, const OptimumRule &rule);

// The frontier: for each R_q level (ascending), the largest V_s with predicted R_q <= level — a
// non-decreasing staircase. levels empty: `n_levels` evenly spaced over the predicted R_q range.
// Columns: rq_level, vs_max, then the inputs and the predicted rq of the point that attains it.
Table frontier(const GridMap &grid, std::size_t vs, std::size_t rq, std::vector<double> levels = {},
               std::size_t n_levels = 50);

}  // namespace spreadmap::analysis
