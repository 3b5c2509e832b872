// The study's Table 4 for a fitted model: per output NRMSE and Pearson R on the training and test
// rows, the cross-validated NRMSE with its spread over folds, the model's noise and signal scales
// where it reports them, and parity rows (true vs predicted).
#pragma once
#include <Eigen/Dense>
#include <nlohmann/json_fwd.hpp>

#include <limits>
#include <string>
#include <vector>

#include "model.hpp"
#include "split.hpp"
#include "table.hpp"

namespace spreadmap::analysis {

struct OutputScores {
  static constexpr double none = std::numeric_limits<double>::quiet_NaN();  // written as null
  std::string name, unit;                      // unit: the output's SI unit, "" when unknown
  double nrmse_train = 0, nrmse_test = 0;      // [%] 100 x RMSE / (max - min of the split's true values)
  double r_train = 0, r_test = 0;              // Pearson R; NaN for fewer than 3 rows or a constant split
  double nrmse_cv = none, nrmse_cv_sd = none;  // [%] out-of-fold NRMSE, pooled; its sd over the folds
  double r_cv = none;                          // Pearson R of the out-of-fold predictions
  double q2_cv = none;    // out-of-fold coefficient of determination, 1 - SSE / SS about the mean
  double rmse_cv = none;  // [unit] out-of-fold root-mean-square error
  double signal_std = none, noise_std = none;  // [unit] the model's fitted scales (surrogate/gp)
};

struct Report {
  std::vector<OutputScores> outputs;
  std::size_t n_train = 0, n_test = 0;
  std::string split, split_reason;        // spelling of the validation used, and why it was chosen
  std::size_t cv_rows = 0, cv_folds = 0;  // rows cross-validated and folds (0: none)
  std::vector<std::string> notes;         // why a score is null, in words
  Table parity;                           // columns: row, split, <out>_true, <out>_predicted [, <out>_std] per output

  // {"split", "split_reason", "n_train", "n_test", "cv_rows", "cv_folds", "nrmse_unit",
  //  "outputs": [{name, unit, nrmse_train, nrmse_test, nrmse_cv, nrmse_cv_sd, r_train, r_test, r_cv,
  //  q2_cv, rmse_cv, signal_std, noise_std}], "notes"}; NaN is written as null.
  nlohmann::json to_json() const;
  // one row per output: output, nrmse_train, nrmse_test, r_train, r_test, nrmse_cv, nrmse_cv_sd,
  // r_cv, signal_std, noise_std, unit
  Table to_table() const;
  void write(const std::string &json_path, const std::string &csv_path) const;  // atomic
  void note(const std::string &text);                                           // adds a note once
};

// Scores a fitted model on all rows of x/y (rows x inputs / outputs), split as given. R on fewer
// than 3 rows is NaN, with a note saying so.
Report make_report(const Model &model, const Eigen::MatrixXd &x, const Eigen::MatrixXd &y, const Split &split,
                   const std::vector<std::string> &output_names);

}  // namespace spreadmap::analysis
