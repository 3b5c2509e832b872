#include "cross_validation.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>

#include "scores.hpp"
#include "summary.hpp"

namespace spreadmap::analysis {

CrossValidation cross_validate(const std::function<std::unique_ptr<Model>()> &make, const Eigen::MatrixXd &x,
                               const Eigen::MatrixXd &y, const std::vector<std::size_t> &rows,
                               const std::vector<Split> &folds, const Eigen::MatrixXd &noise_var) {
  if (folds.size() < 2) throw std::invalid_argument("cross-validation needs at least 2 folds");
  const Eigen::MatrixXd xr = x(rows, Eigen::all), yr = y(rows, Eigen::all);
  const Eigen::MatrixXd vr = noise_var.size() ? Eigen::MatrixXd(noise_var(rows, Eigen::all)) : Eigen::MatrixXd();
  CrossValidation cv;
  cv.rows = rows;
  cv.predicted.resize(yr.rows(), yr.cols());
  cv.fold.assign(rows.size(), 0);
  for (std::size_t k = 0; k < folds.size(); ++k) {
    const Split &f = folds[k];
    for (auto r : f.test) cv.fold.at(r) = k;
    auto m = make();
    if (vr.size()) m->fit_with_noise(xr(f.train, Eigen::all), yr(f.train, Eigen::all), vr(f.train, Eigen::all));
    else m->fit(xr(f.train, Eigen::all), yr(f.train, Eigen::all));
    cv.predicted(f.test, Eigen::all) = m->predict(xr(f.test, Eigen::all)).mean;
  }
  cv.fold_nrmse.assign(std::size_t(y.cols()), {});
  for (Eigen::Index o = 0; o < yr.cols(); ++o) {
    const double range = yr.col(o).maxCoeff() - yr.col(o).minCoeff();
    for (const auto &f : folds) {
      const double e = rmse(yr(f.test, o), cv.predicted(f.test, o));
      cv.fold_nrmse[std::size_t(o)].push_back(range > 0 ? 100 * e / range : std::numeric_limits<double>::quiet_NaN());
    }
  }
  return cv;
}

void score_cross_validation(Report &report, const CrossValidation &cv, const Eigen::MatrixXd &y) {
  const Eigen::MatrixXd yr = y(cv.rows, Eigen::all);
  for (Eigen::Index o = 0; o < yr.cols(); ++o) {
    OutputScores &s = report.outputs.at(std::size_t(o));
    const auto &per_fold = cv.fold_nrmse[std::size_t(o)];
    s.nrmse_cv = nrmse_percent(yr.col(o), cv.predicted.col(o));
    s.nrmse_cv_sd = mean_sd(per_fold).sd;
    s.r_cv = yr.rows() >= min_rows_for_r ? pearson(yr.col(o), cv.predicted.col(o))
                                         : std::numeric_limits<double>::quiet_NaN();
    const double sse = (yr.col(o) - cv.predicted.col(o)).squaredNorm();
    const double sst = (yr.col(o).array() - yr.col(o).mean()).square().sum();
    s.rmse_cv = yr.rows() > 0 ? std::sqrt(sse / double(yr.rows())) : std::numeric_limits<double>::quiet_NaN();
    s.q2_cv = sst > 0 ? 1 - sse / sst : std::numeric_limits<double>::quiet_NaN();
  }
  report.cv_rows = cv.rows.size();
  report.cv_folds = cv.fold_nrmse.empty() ? 0 : cv.fold_nrmse.front().size();
}

}  // namespace spreadmap::analysis
