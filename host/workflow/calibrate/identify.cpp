#include "workflow/calibrate/identify.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace spreadmap::calibrate {
namespace {

// 68.27 % quantile of chi-square with k degrees of freedom.
double delta_chi2(std::size_t k) {
  static const double table[] = {1.00, 2.30, 3.53, 4.72, 5.89, 7.04};
  if (k == 0 || k > 6) throw std::invalid_argument("calibration: 1 to 6 parameters can be identified");
  return table[k - 1];
}

}  // namespace

Identified identify(const std::vector<ParameterRange> &box, const std::vector<MeasuredAngle> &measured,
                    const AnglePredictor &predict, int steps) {
  const std::size_t np = box.size(), nt = measured.size();
  if (steps < 2) throw std::invalid_argument("identify: steps must be >= 2");
  std::size_t points = 1;
  for (std::size_t k = 0; k < np; ++k) points *= std::size_t(steps);
  Eigen::MatrixXd grid(static_cast<Eigen::Index>(points), static_cast<Eigen::Index>(np));
  for (std::size_t g = 0; g < points; ++g) {
    std::size_t rest = g;
    for (std::size_t k = 0; k < np; ++k) {
      const double f = double(rest % std::size_t(steps)) / double(steps - 1);
      grid(Eigen::Index(g), Eigen::Index(k)) = box[k].lo + f * (box[k].hi - box[k].lo);
      rest /= std::size_t(steps);
    }
  }
  const analysis::Prediction pred = predict(grid);
  if (pred.mean.cols() != Eigen::Index(nt))
    throw std::invalid_argument("identify: the surrogate gives " + std::to_string(pred.mean.cols()) +
                                " angles, the measurements are " + std::to_string(nt));
  Eigen::VectorXd chi2(grid.rows());
  for (Eigen::Index g = 0; g < grid.rows(); ++g) {
    double sum = 0;
    for (std::size_t t = 0; t < nt; ++t) {
      const double s = pred.std.size() ? pred.std(g, Eigen::Index(t)) : 0.0;
      const double r = pred.mean(g, Eigen::Index(t)) - measured[t].angle_deg;
      sum += r * r / (measured[t].sigma_deg * measured[t].sigma_deg + s * s);
    }
    chi2(g) = sum;
  }
  Identified out;
  out.grid_points = points;
  out.delta = delta_chi2(np);
  Eigen::Index best = 0;
  out.chi2_min = chi2.minCoeff(&best);
  out.best.resize(np);
  out.lower.assign(np, std::numeric_limits<double>::infinity());
  out.upper.assign(np, -std::numeric_limits<double>::infinity());
  out.open_at_lo.assign(np, false);
  out.open_at_hi.assign(np, false);
  for (std::size_t k = 0; k < np; ++k) out.best[k] = grid(best, Eigen::Index(k));
  for (Eigen::Index g = 0; g < grid.rows(); ++g) {
    if (chi2(g) > out.chi2_min + out.delta) continue;
    ++out.in_set;
    for (std::size_t k = 0; k < np; ++k) {
      const double v = grid(g, Eigen::Index(k));
      out.lower[k] = std::min(out.lower[k], v);
      out.upper[k] = std::max(out.upper[k], v);
      if (v <= box[k].lo) out.open_at_lo[k] = true;
      if (v >= box[k].hi) out.open_at_hi[k] = true;
    }
  }
  for (std::size_t t = 0; t < nt; ++t) {
    out.predicted_deg.push_back(pred.mean(best, Eigen::Index(t)));
    out.predicted_std_deg.push_back(pred.std.size() ? pred.std(best, Eigen::Index(t)) : 0.0);
  }
  return out;
}

}  // namespace spreadmap::calibrate
