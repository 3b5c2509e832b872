#include "workflow/simulate/adaptive_run.hpp"

#include "workflow/run/run_dir.hpp"

#include <spdlog/spdlog.h>

#include <functional>
#include <nlohmann/json.hpp>

#include "analysis/adaptive.hpp"
#include "analysis/multifidelity.hpp"
#include "analysis/plugin_model.hpp"
#include "core/error.hpp"
#include "core/files.hpp"
#include "core/schema.hpp"
#include "workflow/stage/plugin_needs.hpp"
#include "workflow/simulate/case_once.hpp"
#include "workflow/figures/stage_figures.hpp"
#include "workflow/characterise/layer_eval.hpp"

namespace spreadmap {

namespace {

using ModelMaker = std::function<std::unique_ptr<analysis::Model>()>;

// The design's cases as candidate rows, one column per variable.
Eigen::MatrixXd candidate_matrix(const Design &design) {
  const std::size_t n = design.cases.size(), d = design.variables.size();
  Eigen::MatrixXd candidates(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(d));
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t k = 0; k < d; ++k) candidates(Eigen::Index(i), Eigen::Index(k)) = design.cases[i][k];
  return candidates;
}

// The cheap fidelity's scene keys and values.
nlohmann::json cheap_keys_of(const Design &design) {
  nlohmann::json cheap_keys = nlohmann::json::object();
  for (const auto &c : design.cheap) cheap_keys[c.key.name] = c.values.front();
  return cheap_keys;
}

// The design as the manifest records it, before its cases run.
void record_design_in_manifest(StageContext &ctx, const Design &design, std::size_t budget) {
  const bool two_fidelities = design.expensive_budget > 0;
  nlohmann::json variables = nlohmann::json::array();
  for (const auto &v : design.variables) variables.push_back({{"name", v.key.name}, {"unit", v.key.param->unit}});
  const nlohmann::json cheap_keys = cheap_keys_of(design);
  if (two_fidelities) variables.push_back({{"name", analysis::fidelity_input}, {"unit", "-"}});
  ctx.run.update_manifest([&](nlohmann::json &m) {
    m["design"] = {
        {"type", "adaptive"}, {"variables", variables}, {"candidates", design.cases.size()}, {"budget", budget}};
    if (two_fidelities) m["design"]["cheap"] = cheap_keys, m["design"]["expensive_budget"] = design.expensive_budget;
    if (!m.contains("cases")) m["cases"] = nlohmann::json::array();
  });
}

// The design's cases as the adaptive loop asks for them, counting those run now and those finished before.
struct AdaptiveCases {
  StageContext &ctx;
  const Design &design;
  const Eigen::MatrixXd &candidates;
  bool render;
  std::size_t ran = 0, reused = 0;

  // One case: the candidate row, at the cheap fidelity or the expensive one (the workflow's scene).
  // Ids: the row's for the expensive (or only) fidelity, the row's + the candidate count for the cheap.
  Eigen::VectorXd simulate(std::size_t row, bool cheap) {
    const std::size_t n = design.cases.size();
    CaseRequest req;
    req.id = RunDirectory::case_id(cheap ? n + row : row);
    req.scene = case_scene(ctx.scene, design, row, cheap);
    req.inputs = case_inputs(design, row);
    if (design.expensive_budget > 0) req.inputs[analysis::fidelity_input] = cheap ? 0 : 1;
    req.dir = ctx.run.case_dir(req.id);
    req.heaps = ctx.run.heaps();
    bool ran_now = false;
    ensure_case(ctx, req, render, ran_now, "simulate");
    ++(ran_now ? ran : reused);
    const auto r = measure_case_layer(ctx.registry, req.scene, req.dir);
    Eigen::VectorXd y(Eigen::Index(design.outputs.size()));
    for (std::size_t o = 0; o < design.outputs.size(); ++o) {
      const auto &v = r.metrics.value(design.outputs[o], nlohmann::json());
      if (!v.is_number())
        throw RunFailure("adaptive design: " + req.id + " has no value of " + design.outputs[o] +
                         " (empty sampling region?); the design cannot go on");
      y(Eigen::Index(o)) = v.get<double>();
    }
    spdlog::info("adaptive: {} ({}) done", req.id, req.inputs.dump());
    return y;
  }

  std::size_t row_of(const Eigen::VectorXd &x) const {
    const std::size_t n = design.cases.size();
    std::size_t row = 0;
    while (row < n && (candidates.row(Eigen::Index(row)).transpose() - x).norm() > 0) ++row;
    return row;
  }
};

// What the loop did: its fits, the cases it chose, why it stopped, whether it reached the target.
struct AdaptiveOutcome {
  nlohmann::json history = nlohmann::json::array(), chosen = nlohmann::json::array();
  std::string stop_reason;
  bool reached = false;
};

// Two fidelities: many cheap cases, the fewest expensive ones; adds their budgets and counts to the report.
AdaptiveOutcome run_two_fidelities(AdaptiveCases &cases, const ModelMaker &make_model,
                                   const std::vector<std::size_t> &initial, std::size_t budget, double target,
                                   nlohmann::json &report) {
  const Design &design = cases.design;
  const std::size_t n = design.cases.size(), d = design.variables.size();
  analysis::MultiFidelityOptions opt;
  opt.budget_cheap = budget, opt.budget_expensive = design.expensive_budget, opt.target_loo_nrmse = target;
  opt.initial_cheap = initial;
  const auto r = analysis::multi_fidelity_design(
      cases.candidates, make_model,
      [&](const Eigen::VectorXd &x, bool expensive) { return cases.simulate(cases.row_of(x), !expensive); }, opt);
  AdaptiveOutcome out;
  for (const auto &h : r.history)
    out.history.push_back({{"cheap", h.cheap}, {"expensive", h.expensive}, {"loo_nrmse_percent", h.loo_nrmse}});
  for (std::size_t k = 0; k < r.chosen.size(); ++k) {
    const bool expensive = r.x(Eigen::Index(k), Eigen::Index(d)) == 1.0;
    out.chosen.push_back(RunDirectory::case_id(expensive ? r.chosen[k] : n + r.chosen[k]));
  }
  report["cheap"] = cheap_keys_of(design);
  report["budget_cheap"] = budget, report["budget_expensive"] = design.expensive_budget;
  report["cheap_cases"] = r.cheap, report["expensive_cases"] = r.expensive;
  out.stop_reason = r.stop_reason, out.reached = r.reached_target;
  spdlog::info(
      "adaptive: {} cheap and {} expensive cases ({} run now, {} finished before); the map needed {} "
      "expensive runs; stopped: {}",
      r.cheap, r.expensive, cases.ran, cases.reused, r.expensive, r.stop_reason);
  return out;
}

// One fidelity: the most uncertain candidate next, until the target or the budget.
AdaptiveOutcome run_one_fidelity(AdaptiveCases &cases, const ModelMaker &make_model,
                                 const std::vector<std::size_t> &initial, std::size_t budget, double target,
                                 nlohmann::json &report) {
  analysis::AdaptiveOptions opt;
  opt.budget = budget, opt.target_loo_nrmse = target, opt.initial = initial;
  const auto r = analysis::adaptive_design(
      cases.candidates, make_model, [&](const Eigen::VectorXd &x) { return cases.simulate(cases.row_of(x), false); },
      opt);
  AdaptiveOutcome out;
  for (const auto &h : r.history) out.history.push_back({{"cases", h.cases}, {"loo_nrmse_percent", h.loo_nrmse}});
  for (auto c : r.chosen) out.chosen.push_back(RunDirectory::case_id(c));
  report["budget"] = budget;
  out.stop_reason = r.stop_reason, out.reached = r.reached_target;
  spdlog::info("adaptive: {} of {} candidate settings simulated ({} run now, {} finished before); stopped: {}",
               r.chosen.size(), cases.design.cases.size(), cases.ran, cases.reused, r.stop_reason);
  return out;
}

}  // namespace

void run_adaptive_design(StageContext &ctx, const Design &design, bool render) {
  const std::size_t n = design.cases.size(), d = design.variables.size();
  const bool two_fidelities = design.expensive_budget > 0;
  const Eigen::MatrixXd candidates = candidate_matrix(design);

  const LoadedPlugin &model = surrogate_with_std(ctx.registry, "the adaptive design");
  nlohmann::json model_defaults = default_params(*model.descriptor, model.id());
  // Two fidelities: one noise level each (the cheap strip scatters more; a shared one blurs the
  // expensive cases), where the model takes one per value of an input: the fidelity, the input after
  // the design's variables.
  if (two_fidelities && model_defaults.contains("noise_by_input")) model_defaults["noise_by_input"] = d + 1;
  const std::string model_params = model_defaults.dump();
  const std::size_t budget = std::min(design.budget ? design.budget : n, n);
  const double target = design.target_nrmse > 0 ? design.target_nrmse : 1.0;
  std::vector<std::size_t> initial = analysis::space_filling_start(candidates);
  if (design.initial < initial.size()) initial.resize(std::max<std::size_t>(2, design.initial));
  record_design_in_manifest(ctx, design, budget);

  AdaptiveCases cases{ctx, design, candidates, render};
  auto make_model = [&]() -> std::unique_ptr<analysis::Model> {
    return analysis::PluginModel::create(model.descriptor, model_params);
  };
  nlohmann::json report = {{"outputs", design.outputs}, {"target_loo_nrmse_percent", target}, {"candidates", n}, {"model", model.descriptor->name}};
  const AdaptiveOutcome r = two_fidelities ? run_two_fidelities(cases, make_model, initial, budget, target, report)
                                           : run_one_fidelity(cases, make_model, initial, budget, target, report);
  report["cases"] = r.chosen, report["history"] = r.history;
  report["reached_target"] = r.reached, report["stop_reason"] = r.stop_reason;
  write_atomic(ctx.run.root() / "adaptive.json", report.dump(2) + "\n");
}

}  // namespace spreadmap
