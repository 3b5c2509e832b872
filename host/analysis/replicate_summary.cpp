#include "replicate_summary.hpp"

#include <cmath>
#include <map>

namespace spreadmap::analysis {

namespace {
// The cell as a number; NaN when it is empty or not a number (an undefined metric).
double value_or_nan(const Table &t, std::size_t row, std::size_t col) {
  try {
    return t.text(row, col).empty() ? std::nan("") : t.number(row, col);
  } catch (const std::exception &) {
    return std::nan("");
  }
}
}  // namespace

std::string std_column(const std::string &metric) { return metric + "_std"; }

Table summarise_replicates(const Table &runs, const std::string &point, const std::vector<std::string> &inputs,
                           const std::vector<std::string> &metrics, const std::string &source) {
  std::vector<std::string> cols = {"case"};
  cols.insert(cols.end(), inputs.begin(), inputs.end());
  for (const auto &m : metrics) cols.push_back(m), cols.push_back(std_column(m));
  cols.push_back(replicates_column());
  Table out(cols, source);

  const std::size_t point_col = runs.column(point);
  std::vector<std::string> order;
  std::map<std::string, std::vector<std::size_t>> rows_of;
  for (std::size_t r = 0; r < runs.rows(); ++r) {
    const std::string &p = runs.text(r, point_col);
    if (!rows_of.count(p)) order.push_back(p);
    rows_of[p].push_back(r);
  }
  for (const auto &p : order) {
    const auto &rows = rows_of[p];
    std::vector<std::string> cells = {p};
    for (const auto &in : inputs) cells.push_back(runs.text(rows.front(), runs.column(in)));
    for (const auto &m : metrics) {
      std::vector<double> v;
      for (auto r : rows)
        if (const double x = value_or_nan(runs, r, runs.column(m)); std::isfinite(x)) v.push_back(x);
      double mean = 0, ss = 0;
      for (double x : v) mean += x;
      mean /= double(v.size());
      for (double x : v) ss += (x - mean) * (x - mean);
      cells.push_back(v.empty() ? "" : Table::format(mean));
      cells.push_back(v.size() < 2 ? "" : Table::format(std::sqrt(ss / double(v.size() - 1))));
    }
    cells.push_back(std::to_string(rows.size()));
    out.add_row(cells);
  }
  return out;
}

Eigen::MatrixXd replicate_noise_variance(const Table &table, const std::vector<std::string> &outputs,
                                         const std::vector<std::size_t> &rows) {
  Eigen::MatrixXd var = Eigen::MatrixXd::Zero(Eigen::Index(rows.size()), Eigen::Index(outputs.size()));
  if (!table.has_column(replicates_column())) return var;
  const std::size_t n_col = table.column(replicates_column());
  for (std::size_t o = 0; o < outputs.size(); ++o) {
    if (!table.has_column(std_column(outputs[o]))) continue;
    const std::size_t s_col = table.column(std_column(outputs[o]));
    for (std::size_t i = 0; i < rows.size(); ++i) {
      const double sd = value_or_nan(table, rows[i], s_col), n = value_or_nan(table, rows[i], n_col);
      if (std::isfinite(sd) && std::isfinite(n) && n >= 1) var(Eigen::Index(i), Eigen::Index(o)) = sd * sd / n;
    }
  }
  return var;
}

}  // namespace spreadmap::analysis
