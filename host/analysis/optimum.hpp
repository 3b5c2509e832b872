// The most efficient operating point for a wanted roughness, and the trade-off frontier.
// The study: "the rightmost U-omega pair": the largest V_s among points whose predicted R_q is at
// most the target. Here over the evaluated grid (so "within one grid cell" of the true optimum).
#pragma once
#include <Eigen/Dense>
#include <nlohmann/json.hpp>

#include <cstddef>
#include <vector>

#include "grid.hpp"

namespace spreadmap::analysis {

struct Optimum {
  double rq_max = 0;        // the target
  bool found = false;       // false when no grid point meets the target
  std::size_t row = 0;      // grid row
  Eigen::VectorXd x;        // its inputs
  double vs = 0, rq = 0;    // predicted
  double rq_std = -1;       // predicted std of R_q, -1 when the model gives none
  double probability = -1;  // P(R_q <= rq_max) under a normal predictive law, -1 without std
  nlohmann::json to_json(const std::vector<std::string> &input_names) const;
};

// vs, rq: column indices of V_s and R_q among the grid's outputs.
Optimum find_optimum(const GridMap &grid, std::size_t vs, std::size_t rq, double rq_max);
std::vector<Optimum> find_optima(const GridMap &grid, std::size_t vs, std::size_t rq,
                                 const std::vector<double> &rq_max);

// The frontier: for each R_q level (ascending), the largest V_s with predicted R_q <= level — a
// non-decreasing staircase. levels empty: `n_levels` evenly spaced over the predicted R_q range.
// Columns: rq_level, vs_max, then the inputs and the predicted rq of the point that attains it.
Table frontier(const GridMap &grid, std::size_t vs, std::size_t rq, std::vector<double> levels = {},
               std::size_t n_levels = 50);

}  // namespace spreadmap::analysis
