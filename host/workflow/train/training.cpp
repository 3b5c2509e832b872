#include "workflow/train/training.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <cmath>
#include <functional>
#include <nlohmann/json.hpp>
#include <yaml-cpp/yaml.h>

#include "analysis/cross_validation.hpp"
#include "analysis/plugin_model.hpp"
#include "analysis/replicate_summary.hpp"
#include "analysis/scores.hpp"
#include "analysis/split.hpp"
#include "core/error.hpp"
#include "core/files.hpp"
#include "core/schema.hpp"
#include "core/suggest.hpp"
#include "workflow/figures/stage_figures.hpp"
#include "core/units.hpp"
#include "analysis/known_columns.hpp"

namespace spreadmap {

namespace {

// Rows whose inputs and outputs are all numbers: an undefined metric (empty cell) cannot train.
std::vector<std::size_t> usable_rows(const analysis::Table &t, const std::vector<std::size_t> &cols) {
  std::vector<std::size_t> rows;
  for (std::size_t r = 0; r < t.rows(); ++r) {
    bool ok = true;
    for (auto c : cols) {
      try {
        ok = ok && std::isfinite(t.number(r, c));
      } catch (const std::exception &) {
        ok = false;
      }
    }
    if (ok) rows.push_back(r);
  }
  return rows;
}

// The unit of a column: from the units file, matched as column names are (case-insensitively).
analysis::Variable variable(const std::string &name, const Eigen::VectorXd &v,
                            const std::map<std::string, std::string> &units) {
  for (const auto &[k, unit] : units)
    if (lower(k) == lower(name)) return {name, unit, v.minCoeff(), v.maxCoeff()};
  return {name, "", v.minCoeff(), v.maxCoeff()};
}

using analysis::Split;

// Fewest training rows that are cross-validated (folds of 1-2 rows fitted on 2-3 rows below that).
constexpr std::size_t min_cv_rows = 4;

// The rows (indices into `rows`) fitted and tested under v; cross-validation leaves no test rows.
Split split_rows(const analysis::Table &table, const std::vector<std::size_t> &rows, const analysis::Validation &v,
                 std::uint64_t seed) {
  Split split;
  if (v.kind == analysis::Validation::Kind::holdout) return analysis::study_split(rows.size(), seed);
  if (v.kind == analysis::Validation::Kind::column) {
    const Split all = analysis::split_from_column(table, v.column);
    for (std::size_t i = 0; i < rows.size(); ++i) {
      if (std::binary_search(all.train.begin(), all.train.end(), rows[i])) split.train.push_back(i);
      if (std::binary_search(all.test.begin(), all.test.end(), rows[i])) split.test.push_back(i);
    }
    return split;
  }
  for (std::size_t i = 0; i < rows.size(); ++i) split.train.push_back(i);
  return split;
}

// The model's fitted signal and noise standard deviations of output o, when its fit_info() gives
// them as "outputs": [{"signal_std", "noise_std"}, ...] in the output's units (surrogate/gp does).
void add_scales(analysis::OutputScores &s, const nlohmann::json &fit, std::size_t o, const std::string &unit) {
  s.unit = unit;
  if (!fit.contains("outputs") || !fit["outputs"].is_array() || fit["outputs"].size() <= o) return;
  const auto &j = fit["outputs"][o];
  if (j.contains("signal_std") && j["signal_std"].is_number()) s.signal_std = j["signal_std"].get<double>();
  if (j.contains("noise_std") && j["noise_std"].is_number()) s.noise_std = j["noise_std"].get<double>();
}

// The rows that train: those whose inputs and outputs are all numbers, at least 4 of them.
std::vector<std::size_t> training_rows(const analysis::Table &table, const TrainRequest &rq) {
  std::vector<std::size_t> cols;
  for (const auto &name : rq.inputs) cols.push_back(table.column(name));
  for (const auto &name : rq.outputs) cols.push_back(table.column(name));
  std::vector<std::size_t> rows = usable_rows(table, cols);
  if (rows.size() < table.rows())
    spdlog::warn("train: {} of {} rows of {} have an undefined input or output and are left out",
                 table.rows() - rows.size(), table.rows(), table.source());
  if (rows.size() < 4)
    throw InputError("train: " + table.source() + " has " + std::to_string(rows.size()) +
                     " usable rows; a surrogate needs at least 4 (simulate more cases)");
  return rows;
}

// Fits the model on the training rows. Rows that are means of replicated runs carry their scatter
// (`noise`): the model takes it as known noise when it can. True when it did.
bool fit_on_training_rows(analysis::Model &model, const TrainRequest &rq, const Eigen::MatrixXd &x,
                          const Eigen::MatrixXd &y, const Eigen::MatrixXd &noise, const Split &split) {
  const bool known_noise = (noise.array() > 0).any() && model.takes_noise();
  if (known_noise)
    spdlog::info("train {}: the replicate scatter of {} rows is given to the model as their known noise", rq.model,
                 (noise.array() > 0).rowwise().any().count());
  else if ((noise.array() > 0).any())
    spdlog::info("train {}: surrogate/{} takes no known noise: it fits the replicates' means alone", rq.model,
                 rq.model);
  if (known_noise)
    model.fit_with_noise(x(split.train, Eigen::all), y(split.train, Eigen::all), noise(split.train, Eigen::all));
  else model.fit(x(split.train, Eigen::all), y(split.train, Eigen::all));
  return known_noise;
}

// The name of row i of `rows` in the outputs: its case, or its row number when the table has no case column.
std::string case_label(const analysis::Table &table, const std::vector<std::size_t> &rows, std::size_t i) {
  return table.has_column("case") ? table.text(rows[i], table.column("case")) : std::to_string(rows[i]);
}

// Cross-validation over the training rows: all rows under kfold and loo, the training share of a
// holdout (5 folds) beside its test scores. Each fold gets a fresh model fitted without it. Scores the
// report; returns cv.csv: each cross-validated row's true value and its out-of-fold prediction, by output.
analysis::Table cross_validate_training(const std::function<std::unique_ptr<analysis::Model>()> &make,
                                        const Eigen::MatrixXd &x, const Eigen::MatrixXd &y, const Split &split,
                                        const analysis::Validation &v, const TrainRequest &rq,
                                        const analysis::Table &table, const std::vector<std::size_t> &rows,
                                        const Eigen::MatrixXd &known_noise, analysis::Report &report) {
  const std::size_t n_cv = split.train.size();
  const std::size_t k = v.kind == analysis::Validation::Kind::loo     ? n_cv
                        : v.kind == analysis::Validation::Kind::kfold ? v.folds
                                                                      : std::min<std::size_t>(5, n_cv);
  if (k > n_cv)
    throw InputError(
        fmt::format("train: split {} needs at least {} usable rows, {} has {}; use loo or fewer folds",
                    analysis::spelling(v), k, table.source(), n_cv));
  std::vector<std::string> cv_names = {"case", "fold"};
  for (const auto &o : rq.outputs) cv_names.push_back(o + "_true"), cv_names.push_back(o + "_cv");
  analysis::Table cv_table(cv_names, "cv.csv");
  if (n_cv >= min_cv_rows) {
    const auto cv = analysis::cross_validate(make, x, y, split.train, analysis::k_fold(n_cv, k, rq.seed), known_noise);
    analysis::score_cross_validation(report, cv, y);
    for (std::size_t i = 0; i < cv.rows.size(); ++i) {
      std::vector<std::string> cells = {case_label(table, rows, cv.rows[i]), std::to_string(cv.fold[i])};
      for (Eigen::Index c = 0; c < y.cols(); ++c)
        cells.push_back(analysis::Table::format(y(Eigen::Index(cv.rows[i]), c))),
            cells.push_back(analysis::Table::format(cv.predicted(Eigen::Index(i), c)));
      cv_table.add_row(cells);
    }
  } else {
    report.note(
        fmt::format("nrmse_cv is null: {} training rows; cross-validation needs at least {}", n_cv, min_cv_rows));
  }
  return cv_table;
}

// model.json's content: the plugin, its parameters and state, the variables' ranges and units, and
// how it was trained. Adds the model's fitted scales to the report's outputs.
analysis::ModelFile trained_model_file(const LoadedPlugin &plugin, const analysis::Model &model, const TrainRequest &rq,
                                       const Eigen::MatrixXd &x, const Eigen::MatrixXd &y, const analysis::Table &table,
                                       std::size_t rows, analysis::Report &report) {
  analysis::ModelFile file;
  file.plugin = "surrogate/" + rq.model;
  file.plugin_version = plugin.descriptor->version;
  file.params = rq.params;
  for (Eigen::Index i = 0; i < x.cols(); ++i) file.inputs.push_back(variable(rq.inputs[i], x.col(i), rq.units));
  for (Eigen::Index i = 0; i < y.cols(); ++i) file.outputs.push_back(variable(rq.outputs[i], y.col(i), rq.units));
  const nlohmann::json fit = model.fit_info();
  for (std::size_t o = 0; o < report.outputs.size(); ++o) add_scales(report.outputs[o], fit, o, file.outputs[o].unit);
  file.state = model.state();
  file.training = {{"source", table.source()},
                   {"rows", rows},
                   {"split", report.split},
                   {"seed", rq.seed},
                   {"folds", report.cv_folds},
                   {"report", report.to_json()},
                   {"fit", fit}};
  return file;
}

// data.csv: the rows used, their inputs and outputs, and the share (train or test) each was in.
analysis::Table training_data_table(const TrainRequest &rq, const Eigen::MatrixXd &x, const Eigen::MatrixXd &y,
                                    const Split &split, const analysis::Table &table,
                                    const std::vector<std::size_t> &rows) {
  std::vector<std::string> names = {"case"};
  names.insert(names.end(), rq.inputs.begin(), rq.inputs.end());
  names.insert(names.end(), rq.outputs.begin(), rq.outputs.end());
  names.push_back("split");
  analysis::Table data(names, "data.csv");
  const auto labels = analysis::split_labels(split, rows.size());
  for (std::size_t i = 0; i < rows.size(); ++i) {
    std::vector<std::string> cells = {case_label(table, rows, i)};
    for (Eigen::Index c = 0; c < x.cols(); ++c) cells.push_back(analysis::Table::format(x(Eigen::Index(i), c)));
    for (Eigen::Index c = 0; c < y.cols(); ++c) cells.push_back(analysis::Table::format(y(Eigen::Index(i), c)));
    cells.push_back(labels[i]);
    data.add_row(cells);
  }
  return data;
}

}  // namespace

TrainResult train_surrogate(PluginRegistry &registry, const analysis::Table &table, const TrainRequest &rq,
                            const std::filesystem::path &out_dir, bool figures_on) {
  if (rq.inputs.empty() || rq.outputs.empty())
    throw InputError("train: give at least one input and one output column");
  const std::vector<std::size_t> rows = training_rows(table, rq);

  const Eigen::MatrixXd x = table.matrix(rq.inputs, rows), y = table.matrix(rq.outputs, rows);
  const LoadedPlugin &plugin = registry.get("surrogate", rq.model);
  auto make = [&] { return analysis::PluginModel::create(plugin.descriptor, rq.params.dump()); };

  const analysis::Validation v = analysis::resolve_validation(rq.validation, rows.size());
  spdlog::info("train {}: split {}: {} ({})", rq.model, analysis::spelling(v), analysis::describe(v), v.reason);
  const Split split = split_rows(table, rows, v, rq.seed);
  if (split.train.size() < 2) throw InputError("train: fewer than 2 training rows in " + table.source());

  const Eigen::MatrixXd noise = analysis::replicate_noise_variance(table, rq.outputs, rows);
  auto model = make();
  const bool known_noise = fit_on_training_rows(*model, rq, x, y, noise, split);
  analysis::Report report = analysis::make_report(*model, x, y, split, rq.outputs);
  report.split = analysis::spelling(v), report.split_reason = v.reason;

  const analysis::Table cv_table =
      cross_validate_training(make, x, y, split, v, rq, table, rows, known_noise ? noise : Eigen::MatrixXd(), report);
  if (split.test.empty())
    report.note("nrmse_test and r_test are null: " + analysis::describe(v) +
                " holds no rows out for testing; nrmse_cv is the error to expect on new cases");

  analysis::ModelFile file = trained_model_file(plugin, *model, rq, x, y, table, rows.size(), report);
  analysis::Table data = training_data_table(rq, x, y, split, table, rows);

  std::filesystem::create_directories(out_dir);
  analysis::save_model_json((out_dir / "model.json").string(), file);
  report.write((out_dir / "report.json").string(), (out_dir / "report.csv").string());
  report.parity.write_csv((out_dir / "parity.csv").string());
  data.write_csv((out_dir / "data.csv").string());
  cv_table.write_csv((out_dir / "cv.csv").string());
  if (figures_on) figures::parity(report, cv_table, rq.outputs, out_dir / "parity.png");
  return {std::move(file), std::move(report), std::move(data)};
}

std::string score_line(const analysis::Report &report, const analysis::OutputScores &o) {
  const auto known = [](double v) { return std::isfinite(v); };
  std::vector<std::string> errors, r;
  if (known(o.nrmse_cv))
    errors.push_back(fmt::format("cv {:.2f} +- {:.2f} % ({} folds of {} rows)", o.nrmse_cv, o.nrmse_cv_sd,
                                 report.cv_folds, report.cv_rows));
  if (known(o.nrmse_train)) errors.push_back(fmt::format("train {:.2f} %", o.nrmse_train));
  if (known(o.nrmse_test)) errors.push_back(fmt::format("test {:.2f} % ({} rows)", o.nrmse_test, report.n_test));
  if (known(o.r_cv)) r.push_back(fmt::format("cv {:.4f}", o.r_cv));
  if (known(o.r_train)) r.push_back(fmt::format("train {:.4f}", o.r_train));
  if (known(o.r_test)) r.push_back(fmt::format("test {:.4f}", o.r_test));
  std::string line = "NRMSE " + join(errors);
  if (!r.empty()) line += "; R " + join(r);
  if (known(o.noise_std) && known(o.signal_std))
    line += "; noise " + display(o.noise_std, o.unit) + ", signal " + display(o.signal_std, o.unit);
  return line;
}

nlohmann::json surrogate_params(PluginRegistry &registry, const std::string &model,
                                const std::vector<std::string> &assignments) {
  const LoadedPlugin &plugin = registry.get("surrogate", model);
  YAML::Node section(YAML::NodeType::Map);
  for (const auto &a : assignments) {
    const auto eq = a.find('=');
    if (eq == std::string::npos)
      throw InputError("--param " + a + ": write KEY=VALUE, e.g. --param epochs=20000");
    section[a.substr(0, eq)] = a.substr(eq + 1);
  }
  Diagnostics diag;
  auto params = validate_params(SchemaView::of(*plugin.descriptor), section, "<command line>", "--param", diag);
  diag.throw_if_any();
  return params;
}

std::map<std::string, std::string> units_beside(const std::filesystem::path &table_csv) {
  std::map<std::string, std::string> units;
  const auto file = table_csv.parent_path() / (table_csv.stem().string() + ".units.json");
  if (!std::filesystem::exists(file)) {
    // a table from elsewhere: spreadmap's own names are SI by definition (metrics.csv's units)
    std::vector<std::string> named;
    for (const KnownColumn &c : known_columns())
      if (*c.unit) {
        units[c.name] = c.unit;
        named.push_back(std::string(c.name) + " [" + c.unit + "]");
      }
    spdlog::info("{}: no {} beside it: columns named {} are taken as SI, the others as unitless", table_csv.string(),
                 file.filename().string(), join(named, ", "));
    return units;
  }
  try {
    const auto doc = nlohmann::json::parse(read_text(file));
    for (auto &[k, v] : doc.items())
      if (v.is_string()) units[k] = v.get<std::string>();
  } catch (const std::exception &e) {
    spdlog::warn("{}: not read ({}); model.json gets no units", file.string(), e.what());
  }
  return units;
}

}  // namespace spreadmap
