// Which contact parameters reproduce measured bulk angles: the inverse step of calibration.
//
// A surrogate maps the parameters p (friction, rolling friction, ...) to the angle each bulk test
// gives (one output per test), with its standard deviation. Over a fine grid of the parameter box,
//   chi2(p) = sum over tests of (angle_t(p) - measured_t)^2 / (sigma_t^2 + std_t(p)^2),
// the measurement's uncertainty and the surrogate's own added in quadrature. The best p minimises
// chi2; the identified set is {p : chi2(p) <= chi2_min + delta}, delta the 68 % quantile of chi-square
// with as many degrees of freedom as parameters (1.00 for one, 2.30 for two, 3.53 for three), and
// each parameter's interval is that set's extent. One test cannot identify two parameters: the set
// is then a long valley, and its intervals say so.
#pragma once
#include <functional>
#include <string>
#include <vector>

#include "analysis/model.hpp"

namespace spreadmap::calibrate {

struct ParameterRange {
  std::string name;  // a key of the contact law ("friction", "rolling_friction")
  double lo = 0, hi = 0;
};

struct MeasuredAngle {
  std::string test;  // for messages
  double angle_deg = 0, sigma_deg = 0;
};

struct Identified {
  std::vector<double> best;                              // per parameter
  std::vector<double> lower, upper;                      // the identified set's extent, per parameter
  std::vector<bool> open_at_lo, open_at_hi;              // the set reaches the box's side: not bounded there
  std::vector<double> predicted_deg, predicted_std_deg;  // per test, at `best`
  double chi2_min = 0;
  double delta = 0;
  std::size_t grid_points = 0, in_set = 0;
};

// predict: rows of parameter values -> angles (rows x tests) and their std (or empty).
using AnglePredictor = std::function<analysis::Prediction(const Eigen::MatrixXd &)>;

// `steps` grid points per parameter (at least 2); the grid has steps^parameters points.
Identified identify(const std::vector<ParameterRange> &box, const std::vector<MeasuredAngle> &measured,
                    const AnglePredictor &predict, int steps = 101);

}  // namespace spreadmap::calibrate
