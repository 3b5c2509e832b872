// Accuracy scores of the study's Table 4.
#pragma once
#include <Eigen/Dense>

namespace spreadmap::analysis {

double rmse(const Eigen::VectorXd &truth, const Eigen::VectorXd &predicted);
// 100 x RMSE / (max - min of the true values) [%]; NaN when the range is 0 or there are no values.
double nrmse_percent(const Eigen::VectorXd &truth, const Eigen::VectorXd &predicted);
// Fewer rows than this give no Pearson R in a report: through 2 points any line fits (R = +-1).
inline constexpr long min_rows_for_r = 3;
// Pearson correlation coefficient; NaN when either side is constant or there are fewer than 2 values.
double pearson(const Eigen::VectorXd &a, const Eigen::VectorXd &b);

}  // namespace spreadmap::analysis
