#include "report.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <nlohmann/json.hpp>

#include "core/files.hpp"
#include "scores.hpp"

namespace sm = spreadmap;

namespace spreadmap::analysis {

namespace {
Eigen::VectorXd pick(const Eigen::VectorXd &v, const std::vector<std::size_t> &rows) {
  Eigen::VectorXd out(Eigen::Index(rows.size()));
  for (std::size_t i = 0; i < rows.size(); ++i) out[Eigen::Index(i)] = v[Eigen::Index(rows[i])];
  return out;
}
nlohmann::json number_or_null(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

// Pearson R of a split's rows, or NaN with a note when there are too few of them to mean anything.
double r_or_note(Report &r, const char *key, const Eigen::VectorXd &truth, const Eigen::VectorXd &predicted) {
  if (truth.size() >= min_rows_for_r) return pearson(truth, predicted);
  if (truth.size() > 0)
    r.note(std::string(key) + " is null: " + std::to_string(truth.size()) + " rows; Pearson R needs at least " +
           std::to_string(min_rows_for_r) + " (through 2 points it is always +-1)");
  return std::numeric_limits<double>::quiet_NaN();
}
}  // namespace

Report make_report(const Model &model, const Eigen::MatrixXd &x, const Eigen::MatrixXd &y, const Split &split,
                   const std::vector<std::string> &names) {
  if (Eigen::Index(names.size()) != y.cols()) throw std::invalid_argument("report: one name per output expected");
  const Prediction p = model.predict(x);
  Report r;
  r.n_train = split.train.size(), r.n_test = split.test.size();
  std::vector<std::string> cols = {"row", "split"};
  for (const auto &n : names) {
    cols.push_back(n + "_true"), cols.push_back(n + "_predicted");
    if (p.std.size()) cols.push_back(n + "_std");
  }
  r.parity = Table(cols, "parity");
  const auto labels = split_labels(split, std::size_t(x.rows()));
  for (Eigen::Index i = 0; i < x.rows(); ++i) {
    if (labels[std::size_t(i)].empty()) continue;
    std::vector<std::string> row = {std::to_string(i), labels[std::size_t(i)]};
    for (Eigen::Index c = 0; c < y.cols(); ++c) {
      row.push_back(Table::format(y(i, c))), row.push_back(Table::format(p.mean(i, c)));
      if (p.std.size()) row.push_back(Table::format(p.std(i, c)));
    }
    r.parity.add_row(row);
  }
  for (Eigen::Index c = 0; c < y.cols(); ++c) {
    const Eigen::VectorXd t = y.col(c), m = p.mean.col(c);
    OutputScores s;
    s.name = names[std::size_t(c)];
    s.nrmse_train = nrmse_percent(pick(t, split.train), pick(m, split.train));
    s.nrmse_test = nrmse_percent(pick(t, split.test), pick(m, split.test));
    s.r_train = r_or_note(r, "r_train", pick(t, split.train), pick(m, split.train));
    s.r_test = r_or_note(r, "r_test", pick(t, split.test), pick(m, split.test));
    r.outputs.push_back(s);
  }
  return r;
}

nlohmann::json Report::to_json() const {
  nlohmann::json outs = nlohmann::json::array();
  for (const auto &o : outputs)
    outs.push_back({{"name", o.name},
                    {"unit", o.unit},
                    {"nrmse_train", number_or_null(o.nrmse_train)},
                    {"nrmse_test", number_or_null(o.nrmse_test)},
                    {"nrmse_cv", number_or_null(o.nrmse_cv)},
                    {"nrmse_cv_sd", number_or_null(o.nrmse_cv_sd)},
                    {"r_train", number_or_null(o.r_train)},
                    {"r_test", number_or_null(o.r_test)},
                    {"r_cv", number_or_null(o.r_cv)},
                    {"q2_cv", number_or_null(o.q2_cv)},
                    {"rmse_cv", number_or_null(o.rmse_cv)},
                    {"signal_std", number_or_null(o.signal_std)},
                    {"noise_std", number_or_null(o.noise_std)}});
  return {{"split", split},     {"split_reason", split_reason}, {"n_train", n_train}, {"n_test", n_test},
          {"cv_rows", cv_rows}, {"cv_folds", cv_folds},         {"nrmse_unit", "%"},  {"outputs", outs},
          {"notes", notes}};
}

Table Report::to_table() const {
  Table t({"output", "nrmse_train", "nrmse_test", "r_train", "r_test", "nrmse_cv", "nrmse_cv_sd", "r_cv", "signal_std",
           "noise_std", "unit"},
          "report");
  for (const auto &o : outputs)
    t.add_row({o.name, Table::format(o.nrmse_train), Table::format(o.nrmse_test), Table::format(o.r_train),
               Table::format(o.r_test), Table::format(o.nrmse_cv), Table::format(o.nrmse_cv_sd), Table::format(o.r_cv),
               Table::format(o.signal_std), Table::format(o.noise_std), o.unit});
  return t;
}

void Report::note(const std::string &text) {
  if (std::find(notes.begin(), notes.end(), text) == notes.end()) notes.push_back(text);
}

void Report::write(const std::string &json_path, const std::string &csv_path) const {
  write_atomic(json_path, to_json().dump(2) + "\n");
  to_table().write_csv(csv_path);
}

}  // namespace spreadmap::analysis
