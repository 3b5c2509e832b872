// verify: simulates the operating points the map proposes (map/optimum.json: the optimum of every
// rq_max target; targets sharing one point share its runs) with `replicates` new heaps each (default
// 3), measures them as characterise does and compares them with the trained model's prediction and
// its interval (verify/verification.hpp). Writes map/verified.json; a point is verified when the
// simulated mean of V_s and of R_q both fall inside their predicted intervals, the answer when every
// point is. An optimum on the border of the trained box is flagged: the true optimum may lie outside.
// `rounds: N` (default 1) loops: while the answer is not verified and rounds are left, the round's
// runs join the training data (the manifest's verify_cases), characterise, train and map run again
// as the workflow sets them, and the optimum they propose is verified with new heaps. Run again,
// the loop replays its rounds from the same data, so nothing finished is simulated twice.
#include <spdlog/spdlog.h>

#include <optional>
#include <nlohmann/json.hpp>
#include <yaml-cpp/yaml.h>

#include "core/units.hpp"
#include "analysis/multifidelity.hpp"
#include "analysis/replicate_summary.hpp"
#include "analysis/table.hpp"
#include "core/error.hpp"
#include "core/files.hpp"
#include "core/schema.hpp"
#include "workflow/map/mapping.hpp"
#include "workflow/spreading/scene_section.hpp"
#include "workflow/cases/case_runner.hpp"
#include "workflow/cases/replicates.hpp"
#include "workflow/stage/stage.hpp"
#include "workflow/run/run_dir.hpp"
#include "workflow/spreading/scene_model.hpp"
#include "workflow/stage/stage_settings.hpp"
#include "workflow/figures/figure_style.hpp"
#include "workflow/verify/verification.hpp"
#include "workflow/verify/verified_map.hpp"
#include "workflow/verify/verify_runs.hpp"
#include "analysis/known_columns.hpp"

namespace spreadmap {
namespace {

constexpr std::size_t default_runs = 3;

// Per output, the mean over the design points of the replicate scatter^2 (metrics.csv's <output>_std);
// 0 where the runs were not replicated.
std::vector<double> mean_replicate_variance(const fs::path &metrics_csv, const analysis::ModelFile &model) {
  std::vector<double> out(model.outputs.size(), 0.0);
  if (!fs::exists(metrics_csv)) return out;
  const auto table = analysis::Table::read_csv(metrics_csv.string());
  std::vector<std::string> names;
  std::vector<std::size_t> rows;
  for (const auto &o : model.outputs) names.push_back(o.name);
  for (std::size_t r = 0; r < table.rows(); ++r) rows.push_back(r);
  const Eigen::MatrixXd var = analysis::replicate_noise_variance(table, names, rows);
  if (!table.has_column(analysis::replicates_column()) || var.rows() == 0) return out;
  const auto n = table.numbers(analysis::replicates_column());
  for (std::size_t o = 0; o < out.size(); ++o) {
    double sum = 0;
    for (std::size_t r = 0; r < rows.size(); ++r) sum += var(Eigen::Index(r), Eigen::Index(o)) * n[r];  // std^2
    out[o] = sum / double(rows.size());
  }
  return out;
}

constexpr sm_param_v1 verify_schema[] = {
    integer("replicates", 1, max_replicates, default_runs, "runs at the optimum, each with its own heap"),
    integer("rounds", 1, 10, 1, "rounds of verify, refit and propose again until the optimum is verified"),
    table("render", "true, false or the figure's settings {width: 1920, vector: pdf}"),
};

class VerifyStage : public Stage {
 public:
  void validate(const Workflow &wf, const StageEntry &entry, const Scene *scene, PluginRegistry &registry,
                Diagnostics &diag) override {
    const std::string file = wf.file.string();
    style_ = figures::read_style(entry.config["render"], true, false, file, "verify.render", diag);
    runs_ = setting_count(entry.settings, "replicates");
    rounds_ = setting_count(entry.settings, "rounds");
    const StageEntry *map = nullptr, *characterise = nullptr;
    for (std::size_t i = 0; i < wf.stages.size() && &wf.stages[i] != &entry; ++i) {
      if (wf.stages[i].kind == "map") map = &wf.stages[i], map_stage_ = i;
      if (wf.stages[i].kind == "train") train_stage_ = i;
      if (wf.stages[i].kind == "characterise") characterise_stage_ = i;
    }
    for (const auto &s : wf.stages)
      if (s.kind == "characterise") characterise = &s;
    if (rounds_ > 1 && (!characterise_stage_ || !train_stage_))
      diag.error(Location::of(file, entry.config["rounds"]), "verify.rounds",
                 "the verify loop refits the model with its runs: it needs characterise and train stages before it",
                 "add `- characterise` and `- train` before the map stage, or remove rounds");
    if (!map)
      diag.error(entry.where, "verify",
                 "needs a map stage before it: it verifies the optimum the map proposes (map/optimum.json)",
                 "add `- map: {rq_max: [110 um]}` before `- verify`");
    else if (!map->config["rq_max"])
      diag.error(map->where, "map.rq_max", "the verify stage needs an optimum, and a map without rq_max proposes none",
                 "give the map stage a target roughness, e.g. rq_max: [110 um]");
    if (!scene) return;
    if (layered(*scene))
      diag.error(entry.where, "verify", "verifies one pass; a multi-layer scene is not supported yet",
                 "verify the optimum in a workflow that spreads one layer on a plate (scene.layers.count: 1, no "
                 "scene.machine)");
    Diagnostics theirs;  // the characterise stage reports its own problems
    settings_ = read_characterise_settings(wf, characterise ? characterise->config : YAML::Node(YAML::NodeType::Map),
                                           scene, registry, theirs);
    settings_.render = false;  // the verify runs' figures are not drawn
  }

  void run(StageContext &ctx) override {
    history_ = nlohmann::json::array();
    for (std::size_t round = 0;; ++round) {
      figures::use_style(style_);
      const Round r = verify_round(ctx, round);
      if (r.verified || round + 1 >= rounds_) {
        if (rounds_ > 1)
          spdlog::info("verify: {} after {} of {} rounds", r.verified ? "verified" : "NOT verified", round + 1,
                       rounds_);
        return;
      }
      spdlog::info("verify: round {} of {} not verified: its {} runs join the training data and the map proposes again",
                   round + 1, rounds_, r.points.size() * runs_);
      add_runs_to_manifest(ctx, r.points, round);
      refit(ctx, round + 1);
    }
  }

 private:
  struct Round {
    std::vector<VerifyPoint> points;
    bool verified = false;
  };

  // The distinct operating points the map's optima propose, each with the rq_max targets it meets.
  struct Proposed {
    std::vector<VerifyPoint> points;
    std::vector<Eigen::VectorXd> xs;
    std::vector<std::vector<double>> targets;
  };

  static Proposed proposed_points(StageContext &ctx, const analysis::ModelFile &model, const nlohmann::json &optimum,
                                  std::size_t round) {
    Proposed out;
    for (const auto &o : optimum.value("optima", nlohmann::json::array())) {
      if (!o.value("found", false)) {
        spdlog::warn("verify: no optimum for R_q <= {} to verify", display(o.value("rq_max", 0.0), "m"));
        continue;
      }
      Eigen::VectorXd x(Eigen::Index(model.inputs.size()));
      for (std::size_t i = 0; i < model.inputs.size(); ++i) x(Eigen::Index(i)) = o["inputs"][model.inputs[i].name];
      std::size_t p = 0;
      while (p < out.xs.size() && out.xs[p] != x) ++p;
      if (p == out.xs.size()) {
        out.xs.push_back(x), out.targets.emplace_back();
        const std::string id = (round ? "round" + std::to_string(round) + "_v" : "v") + std::to_string(p);
        out.points.push_back({id, point_scene(ctx, model, x), o["inputs"]});
      }
      out.targets[p].push_back(o["rq_max"].get<double>());
    }
    return out;
  }

  // One point's runs against the model's prediction, V_s and R_q each inside its interval or not, as
  // verified.json records it ("verified": both inside).
  nlohmann::json checked_point(StageContext &ctx, const analysis::ModelFile &model, std::size_t vs, std::size_t rq,
                               const VerifyPoint &point, const Eigen::VectorXd &x, const std::vector<double> &targets,
                               const std::vector<nlohmann::json> &simulated,
                               const std::vector<double> &known_var) const {
    const auto predicted = predict_for_runs(ctx.registry, model, x, runs_, known_var);
    nlohmann::json checks = nlohmann::json::object();
    bool verified = true;
    std::vector<bool> met;  // per target: the simulated mean R_q at most rq_max
    for (const auto o : {vs, rq}) {
      const std::string metric = model.outputs[o].name;
      std::vector<double> values;
      for (const auto &m : simulated) {
        const auto &v = m["metrics"].value(metric, nlohmann::json());
        if (!v.is_number())
          throw RunFailure("verify: " + m.value("case", "") + " has no value of " + metric +
                           " (empty sampling region?); see its metrics.json");
        values.push_back(v.get<double>());
      }
      const MetricCheck c = check_metric(metric, model.outputs[o].unit, predicted[o], values);
      verified = verified && c.inside;
      checks[metric] = c.to_json();
      if (o == rq)
        for (double t : targets) met.push_back(c.mean <= t);
      spdlog::info("verify: {} {}: predicted {} +- {} (2 std), simulated {} over {} runs: {}", point.id, metric,
                   display(c.predicted.mean, c.unit), display(2 * c.predicted.std, c.unit), display(c.mean, c.unit),
                   values.size(), c.inside ? "inside" : "OUTSIDE the interval");
    }
    const nlohmann::json edges = edges_of(model, x);
    if (!edges.empty()) spdlog::warn("verify: {} ({}) is {}", point.id, describe(model, x), edge_note());
    std::vector<std::string> cases;
    for (std::size_t r = 0; r < runs_; ++r) cases.push_back("verify/" + replicate_id(point.id, r));
    nlohmann::json out = {
        {"id", point.id},    {"rq_max", targets},    {"rq_max_met", met},         {"inputs", point.inputs},
        {"metrics", checks}, {"verified", verified}, {"at_edge", !edges.empty()}, {"edges", edges},
        {"cases", cases}};
    if (!edges.empty()) out["edge_note"] = edge_note();
    spdlog::info("verify: {} ({}): {}", point.id, describe(model, x),
                 verified ? "verified: the simulation falls inside the predicted interval"
                          : "NOT verified: the simulation falls outside the predicted interval");
    return out;
  }

  // One round: the map's current optimum simulated with new heaps and compared with the model.
  Round verify_round(StageContext &ctx, std::size_t round) {
    const fs::path optimum_json = ctx.run.map_dir() / "optimum.json";
    if (!fs::exists(optimum_json))
      throw InputError("verify: " + optimum_json.string() + " does not exist; run the map stage first");
    const auto optimum = nlohmann::json::parse(read_text(optimum_json));
    const std::string plugin = optimum.value("model", "");
    const std::string name = plugin.substr(plugin.find('/') + 1);
    const auto model = analysis::load_model_json((ctx.run.train_dir(name) / "model.json").string());
    const auto vs = output_index(model, spread_rate_column), rq = output_index(model, roughness_column);
    if (!vs || !rq)
      throw InputError("verify: the model " + plugin + " has no outputs named " + spread_rate_column + " and " +
                       roughness_column);

    const Proposed proposed = proposed_points(ctx, model, optimum, round);
    const std::vector<VerifyPoint> &points = proposed.points;
    if (points.empty())
      throw RunFailure(
          "verify: " + optimum_json.string() +
          " proposes no operating point (no grid point meets any rq_max); raise rq_max or widen the design");

    const auto simulated = run_and_measure(ctx, points, runs_, round * runs_, settings_);
    const auto known_var = mean_replicate_variance(ctx.run.metrics_csv(), model);
    nlohmann::json out_points = nlohmann::json::array();
    bool all = true;
    for (std::size_t p = 0; p < points.size(); ++p) {
      out_points.push_back(
          checked_point(ctx, model, *vs, *rq, points[p], proposed.xs[p], proposed.targets[p], simulated[p], known_var));
      all = all && out_points.back()["verified"].get<bool>();
    }
    nlohmann::json doc = {{"model", plugin}, {"replicates", runs_}, {"points", out_points}, {"verified", all}};
    if (rounds_ > 1) doc["round"] = round + 1, doc["rounds"] = rounds_, doc["earlier_rounds"] = history_;
    write_atomic(ctx.run.map_dir() / "verified.json", doc.dump(2) + "\n");
    history_.push_back({{"round", round + 1}, {"points", out_points}, {"verified", all}});
    // the figure shows the first target's optimum: point v0 when that one was found
    const auto &optima = optimum.value("optima", nlohmann::json::array());
    if (style_.on && !optima.empty() && optima[0].value("found", false))
      redraw_verified_map(ctx, model, optimum, out_points[0]["verified"].get<bool>() ? 1 : 0);
    return {points, all};
  }

  // The round's runs as cases of the manifest's verify_cases (replacing any of the same id), each its
  // own replicate of its point, so that the loop's characterise measures them.
  void add_runs_to_manifest(StageContext &ctx, const std::vector<VerifyPoint> &points, std::size_t round) const {
    ctx.run.update_manifest([&](nlohmann::json &m) {
      nlohmann::json kept = nlohmann::json::array();
      for (const auto &c : m.value("verify_cases", nlohmann::json::array()))
        if (c.value("round", std::size_t(0)) != round) kept.push_back(c);
      for (const auto &p : points)
        for (std::size_t r = 0; r < runs_; ++r) {
          const std::string id = "verify/" + replicate_id(p.id, r);
          kept.push_back({{"id", id},
                          {"dir", id},
                          {"inputs", p.inputs},
                          {"point", "verify/" + p.id},
                          {"replicate", r},
                          {"round", round},
                          {"hash", case_hash(verify_run_scene(p, round * runs_, r))}});
        }
      m["verify_cases"] = kept;
    });
  }

  // characterise (with the runs of the first `rounds` rounds), train and map again, as the workflow sets them.
  void refit(StageContext &ctx, std::size_t rounds) const {
    Diagnostics diag;
    std::vector<std::pair<std::unique_ptr<Stage>, std::size_t>> stages;
    stages.emplace_back(make_characterise_stage(rounds), *characterise_stage_);
    stages.emplace_back(make_train_stage(), *train_stage_);
    stages.emplace_back(make_map_stage(), *map_stage_);
    for (auto &[stage, i] : stages) stage->validate(ctx.wf, ctx.wf.stages[i], &ctx.scene, ctx.registry, diag);
    diag.throw_if_any();
    for (auto &[stage, i] : stages) stage->run(ctx);
  }

  // The workflow's scene at x: each model input is a scene key (U, omega, ...), set as a design does;
  // the fidelity input of a two-fidelity model (held at 1, the expensive one) is the scene as it is.
  static Scene point_scene(StageContext &ctx, const analysis::ModelFile &model, const Eigen::VectorXd &x) {
    Scene scene = ctx.scene;
    for (std::size_t i = 0; i < model.inputs.size(); ++i) {
      if (model.inputs[i].name == analysis::fidelity_input) continue;
      SceneKey key;
      std::string why;
      if (!find_scene_key(ctx.scene, ctx.registry, model.inputs[i].name, key, why))
        throw InputError("verify: the model's input " + model.inputs[i].name +
                         " is not a key of the scene, so its optimum cannot be simulated: " + why);
      apply_scene_value(scene, key, x(Eigen::Index(i)));
    }
    return scene;
  }
  static std::string describe(const analysis::ModelFile &model, const Eigen::VectorXd &x) {
    std::string s;
    for (std::size_t i = 0; i < model.inputs.size(); ++i)
      s += (i ? ", " : "") + model.inputs[i].name + " = " + display(x(Eigen::Index(i)), model.inputs[i].unit);
    return s;
  }

  std::size_t runs_ = default_runs, rounds_ = 1;
  std::optional<std::size_t> characterise_stage_, train_stage_, map_stage_;  // indices in the workflow
  nlohmann::json history_;                                                   // the earlier rounds' points
  CharacteriseSettings settings_;
  figures::Style style_;
};

}  // namespace

std::unique_ptr<Stage> make_verify_stage() { return std::make_unique<VerifyStage>(); }
SchemaView verify_settings() { return {verify_schema, std::size(verify_schema)}; }

}  // namespace spreadmap
