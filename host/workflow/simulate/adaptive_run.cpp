#include "workflow/simulate/adaptive_run.hpp"

#include <spdlog/spdlog.h>

#include "analysis/adaptive.hpp"
#include "analysis/multifidelity.hpp"
#include "analysis/plugin_model.hpp"
#include "core/error.hpp"
#include "core/files.hpp"
#include "core/schema.hpp"
#include "workflow/simulate/case_once.hpp"
#include "workflow/figures/stage_figures.hpp"
#include "workflow/characterise/layer_eval.hpp"

namespace spreadmap {

void run_adaptive_design(StageContext &ctx, const Design &design, bool render) {
  const std::size_t n = design.cases.size(), d = design.variables.size();
  const bool two_fidelities = design.expensive_budget > 0;
  Eigen::MatrixXd candidates(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(d));
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t k = 0; k < d; ++k) candidates(Eigen::Index(i), Eigen::Index(k)) = design.cases[i][k];

  const LoadedPlugin &gp = ctx.registry.get("surrogate", "gp");
  nlohmann::json gp_defaults = default_params(*gp.descriptor, gp.id());
  // Two fidelities: one noise level each (the cheap strip scatters more; a shared one blurs the
  // expensive cases). The fidelity is the input after the design's variables.
  if (two_fidelities) gp_defaults["noise_by_input"] = d + 1;
  const std::string gp_params = gp_defaults.dump();
  const std::size_t budget = std::min(design.budget ? design.budget : n, n);
  const double target = design.target_nrmse > 0 ? design.target_nrmse : 1.0;
  std::vector<std::size_t> initial = analysis::space_filling_start(candidates);
  if (design.initial < initial.size()) initial.resize(std::max<std::size_t>(2, design.initial));

  nlohmann::json variables = nlohmann::json::array();
  for (const auto &v : design.variables) variables.push_back({{"name", v.key.name}, {"unit", v.key.param->unit}});
  nlohmann::json cheap_keys = nlohmann::json::object();
  for (const auto &c : design.cheap) cheap_keys[c.key.name] = c.values.front();
  if (two_fidelities) variables.push_back({{"name", analysis::fidelity_input}, {"unit", "-"}});
  ctx.run.update_manifest([&](nlohmann::json &m) {
    m["design"] = {{"type", "adaptive"}, {"variables", variables}, {"candidates", n}, {"budget", budget}};
    if (two_fidelities) m["design"]["cheap"] = cheap_keys, m["design"]["expensive_budget"] = design.expensive_budget;
    if (!m.contains("cases")) m["cases"] = nlohmann::json::array();
  });

  // One case: the candidate row, at the cheap fidelity or the expensive one (the workflow's scene).
  // Ids: the row's for the expensive (or only) fidelity, the row's + the candidate count for the cheap.
  std::size_t ran = 0, reused = 0;
  auto simulate_row = [&](std::size_t row, bool cheap) -> Eigen::VectorXd {
    CaseRequest req;
    req.id = RunDirectory::case_id(cheap ? n + row : row);
    req.scene = case_scene(ctx.scene, design, row, cheap);
    req.inputs = case_inputs(design, row);
    if (two_fidelities) req.inputs[analysis::fidelity_input] = cheap ? 0 : 1;
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
  };
  auto row_of = [&](const Eigen::VectorXd &x) {
    std::size_t row = 0;
    while (row < n && (candidates.row(Eigen::Index(row)).transpose() - x).norm() > 0) ++row;
    return row;
  };
  auto make_model = [&]() -> std::unique_ptr<analysis::Model> {
    return analysis::PluginModel::create(gp.descriptor, gp_params);
  };

  nlohmann::json report = {{"outputs", design.outputs}, {"target_loo_nrmse_percent", target}, {"candidates", n}};
  nlohmann::json history = nlohmann::json::array(), chosen = nlohmann::json::array();
  std::string stop_reason;
  bool reached = false;
  if (two_fidelities) {
    analysis::MultiFidelityOptions opt;
    opt.budget_cheap = budget, opt.budget_expensive = design.expensive_budget, opt.target_loo_nrmse = target;
    opt.initial_cheap = initial;
    const auto r = analysis::multi_fidelity_design(
        candidates, make_model,
        [&](const Eigen::VectorXd &x, bool expensive) { return simulate_row(row_of(x), !expensive); }, opt);
    for (const auto &h : r.history)
      history.push_back({{"cheap", h.cheap}, {"expensive", h.expensive}, {"loo_nrmse_percent", h.loo_nrmse}});
    for (std::size_t k = 0; k < r.chosen.size(); ++k) {
      const bool expensive = r.x(Eigen::Index(k), Eigen::Index(d)) == 1.0;
      chosen.push_back(RunDirectory::case_id(expensive ? r.chosen[k] : n + r.chosen[k]));
    }
    report["cheap"] = cheap_keys;
    report["budget_cheap"] = budget, report["budget_expensive"] = design.expensive_budget;
    report["cheap_cases"] = r.cheap, report["expensive_cases"] = r.expensive;
    stop_reason = r.stop_reason, reached = r.reached_target;
    spdlog::info(
        "adaptive: {} cheap and {} expensive cases ({} run now, {} finished before); the map needed {} "
        "expensive runs; stopped: {}",
        r.cheap, r.expensive, ran, reused, r.expensive, r.stop_reason);
  } else {
    analysis::AdaptiveOptions opt;
    opt.budget = budget, opt.target_loo_nrmse = target, opt.initial = initial;
    const auto r = analysis::adaptive_design(
        candidates, make_model, [&](const Eigen::VectorXd &x) { return simulate_row(row_of(x), false); }, opt);
    for (const auto &h : r.history) history.push_back({{"cases", h.cases}, {"loo_nrmse_percent", h.loo_nrmse}});
    for (auto c : r.chosen) chosen.push_back(RunDirectory::case_id(c));
    report["budget"] = budget;
    stop_reason = r.stop_reason, reached = r.reached_target;
    spdlog::info("adaptive: {} of {} candidate settings simulated ({} run now, {} finished before); stopped: {}",
                 r.chosen.size(), n, ran, reused, r.stop_reason);
  }
  report["cases"] = chosen, report["history"] = history;
  report["reached_target"] = reached, report["stop_reason"] = stop_reason;
  write_atomic(ctx.run.root() / "adaptive.json", report.dump(2) + "\n");
}

}  // namespace spreadmap
