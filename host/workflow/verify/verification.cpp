#include "workflow/verify/verification.hpp"

#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>

#include "analysis/multifidelity.hpp"
#include "core/error.hpp"
#include "workflow/map/mapping.hpp"

namespace spreadmap {

namespace {
nlohmann::json number_or_null(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(); }

// report.outputs[o][key] of model.json's training record, NaN when absent or null.
double report_value(const analysis::ModelFile &model, std::size_t o, const char *key) {
  const auto &outs = model.training.value("report", nlohmann::json::object()).value("outputs", nlohmann::json());
  if (!outs.is_array() || o >= outs.size() || !outs[o].contains(key) || !outs[o][key].is_number())
    return std::numeric_limits<double>::quiet_NaN();
  return outs[o][key].get<double>();
}
}  // namespace

std::vector<PredictedValue> predict_for_runs(PluginRegistry &registry, const analysis::ModelFile &model,
                                             const Eigen::VectorXd &x, std::size_t runs,
                                             const std::vector<double> &known_var) {
  const auto m = load_model(registry, model);
  const analysis::Prediction p = m->predict(x.transpose());
  std::vector<PredictedValue> out;
  for (std::size_t o = 0; o < model.outputs.size(); ++o) {
    const auto c = Eigen::Index(o);
    PredictedValue v;
    v.mean = p.mean(0, c);
    const double known = o < known_var.size() ? known_var[o] : 0.0;
    if (p.std.size()) {
      const double nugget = report_value(model, o, "noise_std");
      const double noise2 = (std::isfinite(nugget) ? nugget * nugget : 0.0) + known;
      v.std = std::sqrt(p.std(0, c) * p.std(0, c) + noise2 / double(runs));
      v.basis = "predictive std of the mean of " + std::to_string(runs) + " runs";
    } else {
      const double cv = report_value(model, o, "nrmse_cv");
      if (!std::isfinite(cv))
        throw InputError("verify: " + model.plugin + " gives no predictive std and its report no nrmse_cv of " +
                         model.outputs[o].name +
                         ", so it claims no interval to check; train with more cases or use a model that gives a predictive "
                         "standard deviation (spreadmap plugins --kind surrogate)");
      v.std = cv / 100.0 * (model.outputs[o].max - model.outputs[o].min);
      v.basis = "cross-validated RMSE";
    }
    out.push_back(v);
  }
  return out;
}

MetricCheck check_metric(const std::string &name, const std::string &unit, const PredictedValue &predicted,
                         const std::vector<double> &simulated) {
  MetricCheck c{name,     unit, predicted, predicted.mean - 2 * predicted.std, predicted.mean + 2 * predicted.std,
                simulated};
  double ss = 0;
  for (double v : simulated) c.mean += v;
  c.mean /= double(simulated.size());
  for (double v : simulated) ss += (v - c.mean) * (v - c.mean);
  c.std =
      simulated.size() < 2 ? std::numeric_limits<double>::quiet_NaN() : std::sqrt(ss / double(simulated.size() - 1));
  c.inside = c.lower <= c.mean && c.mean <= c.upper;
  return c;
}

nlohmann::json MetricCheck::to_json() const {
  return {{"unit", unit},
          {"predicted", predicted.mean},
          {"predicted_std", predicted.std},
          {"predicted_std_basis", predicted.basis},
          {"interval", {lower, upper}},
          {"simulated", simulated},
          {"simulated_mean", mean},
          {"simulated_std", number_or_null(std)},
          {"inside", inside}};
}

nlohmann::json edges_of(const analysis::ModelFile &model, const Eigen::VectorXd &x) {
  nlohmann::json edges = nlohmann::json::array();
  for (std::size_t i = 0; i < model.inputs.size(); ++i) {
    const auto &v = model.inputs[i];
    const double tol = 1e-9 * std::max(std::abs(v.max - v.min), std::abs(v.max));
    // a fixed input has no border to move; a two-fidelity model is mapped at its expensive fidelity
    if (v.max <= v.min || v.name == analysis::fidelity_input) continue;
    const double xi = x(Eigen::Index(i));
    if (xi <= v.min + tol) edges.push_back({{"input", v.name}, {"side", "min"}});
    else if (xi >= v.max - tol) edges.push_back({{"input", v.name}, {"side", "max"}});
  }
  return edges;
}

}  // namespace spreadmap
