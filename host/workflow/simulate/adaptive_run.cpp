#include "workflow/simulate/adaptive_run.hpp"

#include <spdlog/spdlog.h>

#include "analysis/adaptive.hpp"
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
  Eigen::MatrixXd candidates(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(d));
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t k = 0; k < d; ++k) candidates(Eigen::Index(i), Eigen::Index(k)) = design.cases[i][k];

  const LoadedPlugin &gp = ctx.registry.get("surrogate", "gp");
  const std::string gp_params = default_params(*gp.descriptor, gp.id()).dump();

  analysis::AdaptiveOptions opt;
  opt.budget = std::min(design.budget ? design.budget : n, n);
  opt.target_loo_nrmse = design.target_nrmse > 0 ? design.target_nrmse : 1.0;
  opt.initial = analysis::space_filling_start(candidates);
  if (design.initial < opt.initial.size()) opt.initial.resize(std::max<std::size_t>(2, design.initial));

  nlohmann::json variables = nlohmann::json::array();
  for (const auto &v : design.variables) variables.push_back({{"name", v.key.name}, {"unit", v.key.param->unit}});
  ctx.run.update_manifest([&](nlohmann::json &m) {
    m["design"] = {{"type", "adaptive"}, {"variables", variables}, {"candidates", n}, {"budget", opt.budget}};
    if (!m.contains("cases")) m["cases"] = nlohmann::json::array();
  });

  std::size_t ran = 0, reused = 0;
  auto evaluate = [&](const Eigen::VectorXd &x) -> Eigen::VectorXd {
    std::size_t row = 0;
    while (row < n && (candidates.row(Eigen::Index(row)).transpose() - x).norm() > 0) ++row;
    CaseRequest req;
    req.id = RunDirectory::case_id(row);
    req.scene = case_scene(ctx.scene, design, row);
    req.inputs = case_inputs(design, row);
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
  auto make_model = [&]() -> std::unique_ptr<analysis::Model> {
    return analysis::PluginModel::create(gp.descriptor, gp_params);
  };

  const auto result = analysis::adaptive_design(candidates, make_model, evaluate, opt);
  nlohmann::json history = nlohmann::json::array();
  for (const auto &h : result.history) history.push_back({{"cases", h.cases}, {"loo_nrmse_percent", h.loo_nrmse}});
  nlohmann::json chosen = nlohmann::json::array();
  for (auto c : result.chosen) chosen.push_back(RunDirectory::case_id(c));
  write_atomic(ctx.run.root() / "adaptive.json", nlohmann::json({{"outputs", design.outputs},
                                                                 {"target_loo_nrmse_percent", opt.target_loo_nrmse},
                                                                 {"budget", opt.budget},
                                                                 {"candidates", n},
                                                                 {"cases", chosen},
                                                                 {"history", history},
                                                                 {"reached_target", result.reached_target},
                                                                 {"stop_reason", result.stop_reason}})
                                                         .dump(2) +
                                                     "\n");
  spdlog::info("adaptive: {} of {} candidate settings simulated ({} run now, {} finished before); stopped: {}",
               result.chosen.size(), n, ran, reused, result.stop_reason);
}

}  // namespace spreadmap
