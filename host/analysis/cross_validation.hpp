// Cross-validation of a surrogate: each fold's rows predicted by a model fitted to the other rows,
// and the scores of those out-of-fold predictions for the report.
#pragma once
#include <Eigen/Dense>

#include <functional>
#include <memory>
#include <vector>

#include "model.hpp"
#include "report.hpp"
#include "split.hpp"

namespace spreadmap::analysis {

struct CrossValidation {
  std::vector<std::size_t> rows;  // the rows of x and y that were cross-validated, ascending
  Eigen::MatrixXd predicted;      // rows.size() x outputs: out-of-fold predictions, in `rows` order
  std::vector<std::size_t> fold;  // the fold that predicted each of `rows`
  // [output][fold]: 100 x RMSE of the fold / range of the output over all cross-validated rows [%].
  // One range for every fold, so that folds of one row (leave-one-out) are scored too.
  std::vector<std::vector<double>> fold_nrmse;
};

// folds index into `rows` (0 .. rows.size()-1); a fresh model from make() per fold. noise_var: the
// known variance of each y (as y, rows of x), given to each fold's fit; empty when none.
CrossValidation cross_validate(const std::function<std::unique_ptr<Model>()> &make, const Eigen::MatrixXd &x,
                               const Eigen::MatrixXd &y, const std::vector<std::size_t> &rows,
                               const std::vector<Split> &folds, const Eigen::MatrixXd &noise_var = {});

// Fills each output's nrmse_cv (pooled over all rows), nrmse_cv_sd (sample standard deviation over
// the folds) and r_cv (Pearson R of the out-of-fold predictions; NaN below 3 rows), and the
// report's cv_rows and cv_folds. y: all rows, as given to cross_validate.
void score_cross_validation(Report &report, const CrossValidation &cv, const Eigen::MatrixXd &y);

}  // namespace spreadmap::analysis
