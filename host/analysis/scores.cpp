#include "scores.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>

namespace sm = spreadmap;

namespace spreadmap::analysis {

namespace {
void same_size(const Eigen::VectorXd &a, const Eigen::VectorXd &b) {
  if (a.size() != b.size()) throw std::invalid_argument("scores: the true and predicted vectors differ in length");
}
constexpr double nan = std::numeric_limits<double>::quiet_NaN();
}  // namespace

double rmse(const Eigen::VectorXd &t, const Eigen::VectorXd &p) {
  same_size(t, p);
  return t.size() ? std::sqrt((t - p).squaredNorm() / double(t.size())) : nan;
}

double nrmse_percent(const Eigen::VectorXd &t, const Eigen::VectorXd &p) {
  same_size(t, p);
  if (t.size() == 0) return nan;
  const double range = t.maxCoeff() - t.minCoeff();
  return range > 0 ? 100.0 * rmse(t, p) / range : nan;
}

double pearson(const Eigen::VectorXd &a, const Eigen::VectorXd &b) {
  same_size(a, b);
  if (a.size() < 2) return nan;
  const Eigen::ArrayXd da = a.array() - a.mean(), db = b.array() - b.mean();
  const double saa = da.square().sum(), sbb = db.square().sum();
  return saa > 0 && sbb > 0 ? (da * db).sum() / std::sqrt(saa * sbb) : nan;
}

}  // namespace spreadmap::analysis
