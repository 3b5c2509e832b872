#include "workflow/train/training.hpp"

#include <spdlog/spdlog.h>

#include <cmath>

#include "analysis/plugin_model.hpp"
#include "analysis/scores.hpp"
#include "analysis/split.hpp"
#include "core/error.hpp"
#include "core/files.hpp"
#include "core/schema.hpp"
#include "core/suggest.hpp"
#include "workflow/figures/stage_figures.hpp"

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

}  // namespace

TrainResult train_surrogate(PluginRegistry &registry, const analysis::Table &table, const TrainRequest &rq,
                            const std::filesystem::path &out_dir, bool figures_on) {
  if (rq.inputs.empty() || rq.outputs.empty())
    throw InputError("error: train: give at least one input and one output column");
  std::vector<std::size_t> cols;
  for (const auto &name : rq.inputs) cols.push_back(table.column(name));
  for (const auto &name : rq.outputs) cols.push_back(table.column(name));
  std::vector<std::size_t> rows = usable_rows(table, cols);
  if (rows.size() < table.rows())
    spdlog::warn("train: {} of {} rows of {} have an undefined input or output and are left out",
                 table.rows() - rows.size(), table.rows(), table.source());
  if (rows.size() < 4)
    throw InputError("error: train: " + table.source() + " has " + std::to_string(rows.size()) +
                     " usable rows; a surrogate needs at least 4 (simulate more cases)");

  const Eigen::MatrixXd x = table.matrix(rq.inputs, rows), y = table.matrix(rq.outputs, rows);
  const LoadedPlugin &plugin = registry.get("surrogate", rq.model);
  auto make = [&] { return analysis::PluginModel::create(plugin.descriptor, rq.params.dump()); };

  analysis::Split split;
  std::vector<analysis::Split> folds;
  if (rq.split == "study") {
    split = analysis::study_split(rows.size(), rq.seed);
  } else if (rq.split == "column") {
    const analysis::Split all = analysis::split_from_column(table, rq.split_column);
    for (std::size_t i = 0; i < rows.size(); ++i) {
      if (std::binary_search(all.train.begin(), all.train.end(), rows[i])) split.train.push_back(i);
      if (std::binary_search(all.test.begin(), all.test.end(), rows[i])) split.test.push_back(i);
    }
  } else if (rq.split == "kfold") {
    folds = analysis::k_fold(rows.size(), rq.folds, rq.seed);
    for (std::size_t i = 0; i < rows.size(); ++i) split.train.push_back(i);
  } else {
    throw InputError("error: train: split '" + rq.split + "' is not one of study, kfold, column");
  }
  if (split.train.size() < 2) throw InputError("error: train: fewer than 2 training rows in " + table.source());

  auto model = make();
  model->fit(x(split.train, Eigen::all), y(split.train, Eigen::all));
  analysis::Report report = analysis::make_report(*model, x, y, split, rq.outputs);

  if (!folds.empty()) {
    // Out-of-fold predictions: each row predicted by the model that did not see it.
    Eigen::MatrixXd oof(y.rows(), y.cols());
    for (const auto &f : folds) {
      auto m = make();
      m->fit(x(f.train, Eigen::all), y(f.train, Eigen::all));
      oof(f.test, Eigen::all) = m->predict(x(f.test, Eigen::all)).mean;
    }
    for (Eigen::Index o = 0; o < y.cols(); ++o) {
      report.outputs[o].nrmse_test = analysis::nrmse_percent(y.col(o), oof.col(o));
      report.outputs[o].r_test = analysis::pearson(y.col(o), oof.col(o));
    }
    report.n_test = rows.size();
  }

  analysis::ModelFile file;
  file.plugin = "surrogate/" + rq.model;
  file.plugin_version = plugin.descriptor->version;
  file.params = rq.params;
  for (Eigen::Index i = 0; i < x.cols(); ++i) file.inputs.push_back(variable(rq.inputs[i], x.col(i), rq.units));
  for (Eigen::Index i = 0; i < y.cols(); ++i) file.outputs.push_back(variable(rq.outputs[i], y.col(i), rq.units));
  file.state = model->state();
  file.training = {{"source", table.source()},
                   {"rows", rows.size()},
                   {"split", rq.split},
                   {"seed", rq.seed},
                   {"folds", folds.empty() ? 0 : rq.folds},
                   {"report", report.to_json()},
                   {"fit", model->fit_info()}};

  analysis::Table data(std::vector<std::string>{"case"}, "data.csv");
  {
    std::vector<std::string> names = {"case"};
    names.insert(names.end(), rq.inputs.begin(), rq.inputs.end());
    names.insert(names.end(), rq.outputs.begin(), rq.outputs.end());
    names.push_back("split");
    data = analysis::Table(names, "data.csv");
    const auto labels = analysis::split_labels(folds.empty() ? split : analysis::Split{split.train, {}}, rows.size());
    const bool has_case = table.has_column("case");
    for (std::size_t i = 0; i < rows.size(); ++i) {
      std::vector<std::string> cells = {has_case ? table.text(rows[i], table.column("case")) : std::to_string(rows[i])};
      for (Eigen::Index c = 0; c < x.cols(); ++c) cells.push_back(analysis::Table::format(x(Eigen::Index(i), c)));
      for (Eigen::Index c = 0; c < y.cols(); ++c) cells.push_back(analysis::Table::format(y(Eigen::Index(i), c)));
      cells.push_back(labels[i]);
      data.add_row(cells);
    }
  }

  std::filesystem::create_directories(out_dir);
  analysis::save_model_json((out_dir / "model.json").string(), file);
  report.write((out_dir / "report.json").string(), (out_dir / "report.csv").string());
  report.parity.write_csv((out_dir / "parity.csv").string());
  data.write_csv((out_dir / "data.csv").string());
  if (figures_on) figures::parity(report, rq.outputs, out_dir / "parity.png");
  return {std::move(file), std::move(report), std::move(data)};
}

nlohmann::json surrogate_params(PluginRegistry &registry, const std::string &model,
                                const std::vector<std::string> &assignments) {
  const LoadedPlugin &plugin = registry.get("surrogate", model);
  YAML::Node section(YAML::NodeType::Map);
  for (const auto &a : assignments) {
    const auto eq = a.find('=');
    if (eq == std::string::npos)
      throw InputError("error: --param " + a + ": write KEY=VALUE, e.g. --param epochs=20000");
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
    units = {{"U", "m/s"}, {"omega", "rad/s"},   {"vs", "m^2/s"},
             {"rq", "m"},  {"mean_height", "m"}, {"solid_thickness", "m"}};
    spdlog::info(
        "{}: no {} beside it: columns named U, omega, vs, rq, mean_height, solid_thickness are taken as SI "
        "(m/s, rad/s, m^2/s, m), the others as unitless",
        table_csv.string(), file.filename().string());
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
