#include "workflow/map/mapping.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "core/files.hpp"
#include "analysis/multifidelity.hpp"
#include "core/suggest.hpp"
#include "workflow/figures/stage_figures.hpp"
#include "analysis/known_columns.hpp"

namespace spreadmap {

namespace {

// A loaded model that refuses to hand out numbers nobody can trust: a map, an optimum or a query
// built on NaN or infinite predictions would look like an answer.
class CheckedModel : public analysis::Model {
 public:
  CheckedModel(std::unique_ptr<analysis::PluginModel> model, const analysis::ModelFile &file)
      : model_(std::move(model)), source_(file.path.empty() ? file.plugin : file.path) {
    for (const auto &o : file.outputs) outputs_.push_back(o.name);
  }
  void fit(const Eigen::MatrixXd &x, const Eigen::MatrixXd &y) override { model_->fit(x, y); }
  analysis::Prediction predict(const Eigen::MatrixXd &x) const override {
    analysis::Prediction p = model_->predict(x);
    check(p.mean, "prediction");
    check(p.std, "predictive std");
    return p;
  }
  bool has_std() const override { return model_->has_std(); }
  nlohmann::json state() const override { return model_->state(); }
  void load(const nlohmann::json &state) override { model_->load(state); }
  nlohmann::json fit_info() const override { return model_->fit_info(); }

 private:
  void check(const Eigen::MatrixXd &values, const char *what) const {
    for (Eigen::Index c = 0; c < values.cols(); ++c)
      if (!values.col(c).allFinite())
        throw InputError(source_ + ": the model's " + what + " of " + outputs_.at(std::size_t(c)) +
                         " is not a finite number (its saved state is damaged or out of range); train it "
                         "again (spreadmap train, or spreadmap run --only train --force)");
  }
  std::unique_ptr<analysis::PluginModel> model_;
  std::string source_;
  std::vector<std::string> outputs_;
};

}  // namespace

std::unique_ptr<analysis::Model> load_model(PluginRegistry &registry, const analysis::ModelFile &file) {
  const LoadedPlugin &plugin = registry.get("surrogate", file.plugin_name());
  auto model = analysis::PluginModel::create(plugin.descriptor, file.params.dump());
  model->load(file.state, Eigen::Index(file.outputs.size()));
  return std::make_unique<CheckedModel>(std::move(model), file);
}

std::optional<std::size_t> output_index(const analysis::ModelFile &file, const std::string &name) {
  for (std::size_t i = 0; i < file.outputs.size(); ++i)
    if (iequals(file.outputs[i].name, name)) return i;
  return std::nullopt;
}

std::vector<std::string> MapResult::untrusted_basis() const {
  std::vector<std::string> out;
  for (const auto &t : trust)
    if (t.untrusted() && is_contract_metric(t.output)) out.push_back(t.output);
  return out;
}

namespace {
// The spread the confidence rule uses: the model's own predictive std, else (a model without
// uncertainty, e.g. surrogate/bpnn) its cross-validated RMSE of R_q, the error it made on cases it
// was not fitted to, taken as one normal spread for every point of the grid.
analysis::OptimumRule optimum_rule(const analysis::ModelFile &file, const MapResult &m, double confidence) {
  analysis::OptimumRule rule;
  rule.confidence = confidence;
  if (m.grid.prediction.std.size() > 0 || confidence == 0.5) return rule;
  const auto &rq_trust = m.trust.at(*m.rq);
  if (!std::isfinite(rq_trust.rmse_cv))
    throw InputError(fmt::format(
        "map: confidence {} needs the predictive spread of R_q, and {} gives none: its model.json holds no "
        "cross-validated RMSE either ({}); set confidence: 0.5 to choose by the predicted mean, or retrain with "
        "cross-validation (at least 4 rows)",
        confidence, file.plugin, rq_trust.reason));
  rule.fallback_rq_std = rq_trust.rmse_cv;
  rule.std_source = "cross-validation";
  return rule;
}
}  // namespace

MapResult make_process_map(PluginRegistry &registry, const analysis::ModelFile &file, const MapRequest &rq) {
  const auto model = load_model(registry, file);
  // A model of two fidelities answers for the expensive one: its fidelity input is held at 1, and
  // the grid's points are those of the other inputs.
  const auto points = rq.points.empty() ? analysis::default_grid_points(mapped_inputs(file)) : rq.points;
  std::vector<analysis::Axis> axes;
  for (std::size_t i = 0, k = 0; i < file.inputs.size(); ++i) {
    const auto &v = file.inputs[i];
    if (v.name == analysis::fidelity_input) {
      axes.push_back({v.name, 1.0, 1.0, 1});
      continue;
    }
    const std::size_t n = points.at(k++);
    axes.push_back({v.name, v.min, v.max, v.min == v.max ? 1 : n});
  }
  std::vector<std::string> outputs;
  for (const auto &o : file.outputs) outputs.push_back(o.name);
  MapResult m{analysis::evaluate_grid(*model, axes, outputs),
              output_index(file, spread_rate_column),
              output_index(file, roughness_column),
              {},
              {},
              analysis::judge_map_trust(file),
              rq.confidence};
  if (m.vs && m.rq) {
    m.optima = analysis::find_optima(m.grid, *m.vs, *m.rq, rq.rq_max, optimum_rule(file, m, rq.confidence));
    m.frontier = analysis::frontier(m.grid, *m.vs, *m.rq);
  } else if (!rq.rq_max.empty()) {
    throw InputError("map: an optimum needs outputs named vs and rq; this model has " + [&] {
      std::vector<std::string> n;
      for (const auto &o : file.outputs) n.push_back(o.name);
      return join(n);
    }());
  }
  return m;
}

void write_process_map(const MapResult &m, const analysis::ModelFile &file, const std::filesystem::path &dir,
                       const analysis::Table *training, bool figures_on) {
  std::filesystem::create_directories(dir);
  m.grid.to_table().write_csv((dir / "map.csv").string());
  std::vector<std::string> names;
  for (const auto &v : file.inputs) names.push_back(v.name);
  nlohmann::json optima = nlohmann::json::array();
  for (const auto &o : m.optima) optima.push_back(o.to_json(names));
  nlohmann::json units = nlohmann::json::object();
  for (const auto &v : file.inputs) units[v.name] = v.unit;
  for (const auto &v : file.outputs) units[v.name] = v.unit;
  nlohmann::json trust = nlohmann::json::object();
  for (const auto &t : m.trust) trust[t.output] = t.to_json();
  const auto untrusted = m.untrusted_basis();
  for (auto &o : optima)
    if (o.value("found", false)) o["rests_on_untrusted"] = untrusted;
  write_atomic(dir / "optimum.json", nlohmann::json({{"model", file.plugin},
                                                     {"units", units},
                                                     {"confidence", m.confidence},
                                                     {"trust", trust},
                                                     {"optima", optima}})
                                             .dump(2) +
                                         "\n");
  if (m.vs && m.rq) m.frontier.write_csv((dir / "frontier.csv").string());
  if (!figures_on) return;
  std::vector<std::string> out_units;
  for (const auto &v : file.outputs) out_units.push_back(v.unit);
  figures::surfaces(m.grid, out_units, training ? *training : analysis::Table(), dir);
  if (m.vs && m.rq)
    figures::process_map(m.grid, *m.vs, *m.rq, m.frontier, m.optima, dir / "map.png",
                         training ? *training : analysis::Table(), -1, m.trust);
}

std::string describe_optimum(const analysis::Optimum &o, const analysis::ModelFile &file) {
  std::string at;
  for (std::size_t i = 0; i < file.inputs.size(); ++i)
    at += (i ? ", " : "") + file.inputs[i].name + " = " + display(o.x(Eigen::Index(i)), file.inputs[i].unit);
  std::string text = fmt::format("{}: V_s = {}, R_q = {}", at, display(o.vs, "m^2/s"), display(o.rq, "m"));
  if (o.rq_std >= 0)
    text += fmt::format(" +- {}, P(R_q <= {}) = {:.2f}", display(o.rq_std, "m"), display(o.rq_max, "m"), o.probability);
  return text;
}

double parse_confidence(const std::string &text, const std::string &where) {
  double value = 0;
  try {
    std::size_t used = 0;
    value = std::stod(text, &used);
    std::string rest = text.substr(used);
    rest.erase(0, rest.find_first_not_of(' '));
    if (rest == "%") value /= 100;
    else if (!rest.empty()) throw std::invalid_argument("trailing text");
  } catch (const std::exception &) {
    throw InputError(where + ": '" + text + "' is not a probability; write e.g. 0.9 or 90 %");
  }
  if (!(value >= 0.5 && value < 1))
    throw InputError(fmt::format("{}: {} is outside [0.5, 1): 0.5 chooses by the predicted mean, 0.9 asks "
                                 "P(R_q <= target) >= 0.9",
                                 where, text));
  return value;
}

std::size_t mapped_inputs(const analysis::ModelFile &file) {
  std::size_t n = 0;
  for (const auto &v : file.inputs) n += v.name != analysis::fidelity_input;
  return n;
}

std::vector<std::size_t> parse_grid_points(const std::string &text, std::size_t inputs) {
  std::vector<std::size_t> out;
  std::size_t pos = 0;
  while (pos <= text.size()) {
    const auto x = text.find_first_of("xX", pos);
    const std::string part = text.substr(pos, x == std::string::npos ? std::string::npos : x - pos);
    try {
      std::size_t used = 0;
      const long v = std::stol(part, &used);
      if (used != part.size() || v < 2 || v > 100000) throw std::invalid_argument("range");
      out.push_back(std::size_t(v));
    } catch (const std::exception &) {
      throw InputError("--grid " + text + ": write points per input as NXxNY with each at least 2, e.g. 101x81");
    }
    if (x == std::string::npos) break;
    pos = x + 1;
  }
  if (out.size() != inputs)
    throw InputError(
        fmt::format("--grid {}: the map has {} inputs, the grid gives {}", text, inputs, out.size()));
  return out;
}


}  // namespace spreadmap
