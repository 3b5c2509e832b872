// The study's Table 4 for a fitted model: per output NRMSE and Pearson R on the training and test
// rows, plus parity rows (true vs predicted).
#pragma once
#include <Eigen/Dense>
#include <nlohmann/json.hpp>

#include <string>
#include <vector>

#include "model.hpp"
#include "split.hpp"
#include "table.hpp"

namespace spreadmap::analysis {

struct OutputScores {
  std::string name;
  double nrmse_train = 0, nrmse_test = 0;  // [%] 100 x RMSE / (max - min of the split's true values)
  double r_train = 0, r_test = 0;          // Pearson R; NaN for an empty or constant split
};

struct Report {
  std::vector<OutputScores> outputs;
  std::size_t n_train = 0, n_test = 0;
  Table parity;  // columns: row, split, <out>_true, <out>_predicted [, <out>_std] per output

  nlohmann::json to_json() const;  // {"n_train", "n_test", "outputs": [{name, nrmse_train, ...}]}
  Table to_table() const;          // one row per output: output, nrmse_train, nrmse_test, r_train, r_test
  void write(const std::string &json_path, const std::string &csv_path) const;  // atomic
};

// Scores a fitted model on all rows of x/y (rows x inputs / outputs), split as given.
Report make_report(const Model &model, const Eigen::MatrixXd &x, const Eigen::MatrixXd &y, const Split &split,
                   const std::vector<std::string> &output_names);

}  // namespace spreadmap::analysis
