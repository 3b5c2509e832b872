#include "grid.hpp"

#include <stdexcept>

namespace sm = spreadmap;

namespace spreadmap::analysis {

std::vector<std::size_t> default_grid_points(std::size_t n) {
  if (n == 2) return {101, 81};
  if (n == 1) return {101};
  return std::vector<std::size_t>(n, 21);
}

Eigen::MatrixXd grid_points(const std::vector<Axis> &axes) {
  if (axes.empty()) throw std::invalid_argument("grid: no axes");
  Eigen::Index rows = 1;
  for (const auto &a : axes) {
    if (a.points < 1 || (a.points < 2 && a.max != a.min) || !(a.max >= a.min))
      throw std::invalid_argument("grid: axis '" + a.name + "' needs min <= max and >= 2 points");
    rows *= Eigen::Index(a.points);
  }
  Eigen::MatrixXd x(rows, Eigen::Index(axes.size()));
  for (Eigen::Index r = 0; r < rows; ++r) {
    Eigen::Index rest = r;
    for (std::size_t k = axes.size(); k-- > 0;) {
      const auto &a = axes[k];
      const Eigen::Index i = rest % Eigen::Index(a.points);
      rest /= Eigen::Index(a.points);
      // Exact end points: min + (max - min) * i / (n - 1) hits max at i = n - 1.
      x(r, Eigen::Index(k)) = a.points < 2 ? a.min : a.min + (a.max - a.min) * double(i) / double(a.points - 1);
    }
  }
  return x;
}

GridMap evaluate_grid(const Model &model, const std::vector<Axis> &axes, const std::vector<std::string> &outputs) {
  GridMap g;
  for (const auto &a : axes) g.inputs.push_back(a.name);
  g.outputs = outputs;
  g.x = grid_points(axes);
  g.prediction = model.predict(g.x);
  if (g.prediction.mean.cols() != Eigen::Index(outputs.size()))
    throw std::invalid_argument("grid: the model predicts " + std::to_string(g.prediction.mean.cols()) + " outputs, " +
                                std::to_string(outputs.size()) + " names given");
  return g;
}

Table GridMap::to_table() const {
  std::vector<std::string> cols = inputs;
  cols.insert(cols.end(), outputs.begin(), outputs.end());
  const bool with_std = prediction.std.size() > 0;
  if (with_std)
    for (const auto &o : outputs) cols.push_back(o + "_std");
  Table t(cols, "map");
  for (Eigen::Index r = 0; r < x.rows(); ++r) {
    std::vector<double> row;
    for (Eigen::Index c = 0; c < x.cols(); ++c) row.push_back(x(r, c));
    for (Eigen::Index c = 0; c < prediction.mean.cols(); ++c) row.push_back(prediction.mean(r, c));
    if (with_std)
      for (Eigen::Index c = 0; c < prediction.std.cols(); ++c) row.push_back(prediction.std(r, c));
    t.add_row(row);
  }
  return t;
}

}  // namespace spreadmap::analysis
