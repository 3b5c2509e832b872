// Evaluates a model over a full grid of its input box (the process map's raw material).
#pragma once
#include <Eigen/Dense>

#include <string>
#include <vector>

#include "model.hpp"
#include "table.hpp"

namespace spreadmap::analysis {

struct Axis {
  std::string name;
  double min = 0, max = 0;  // SI
  std::size_t points = 2;   // >= 2 unless min == max
};

// The default resolution: 101 x 81 for two inputs (U, omega), 101 for one, 21 per input above two.
std::vector<std::size_t> default_grid_points(std::size_t n_inputs);
// Rows of every grid point, the first axis varying slowest.
Eigen::MatrixXd grid_points(const std::vector<Axis> &axes);

struct GridMap {
  std::vector<std::string> inputs, outputs;
  Eigen::MatrixXd x;      // rows x inputs
  Prediction prediction;  // rows x outputs (std empty when the model gives none)
  // Columns: inputs, outputs, then <output>_std for each output when std is given.
  Table to_table() const;
};

GridMap evaluate_grid(const Model &model, const std::vector<Axis> &axes, const std::vector<std::string> &outputs);

}  // namespace spreadmap::analysis
