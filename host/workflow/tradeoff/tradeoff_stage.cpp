// tradeoff: one scene at several fidelities, each run on several random heaps, to measure what a
// cheaper setting costs in accuracy. The most expensive fidelity (most particle-steps) is the
// reference; for each fidelity: wall time, particle-steps, V_s and R_q with their heap-to-heap
// scatter, and their error against the reference in per cent and in units of the combined
// standard error. Writes tradeoff/tradeoff.csv, tradeoff/tradeoff.md and tradeoff/tradeoff.png (the
// error of each fidelity over its wall time, log-log).
//
//   - tradeoff:
//       heaps: 3
//       fidelities:
//         - {name: reference, time.safety: 0.2, contact.overlap_max: 2.5 um}
//         - {name: float, precision: float}
//
// A contact.* key sets the particle-particle law and the substrate and spreader laws alike.
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <yaml-cpp/yaml.h>

#include "analysis/summary.hpp"
#include "analysis/table.hpp"
#include "core/error.hpp"
#include "core/files.hpp"
#include "core/schema.hpp"
#include "workflow/simulate/case_once.hpp"
#include "workflow/figures/figure_style.hpp"
#include "workflow/figures/stage_figures.hpp"
#include "workflow/spreading/scene_section.hpp"
#include "workflow/stage/stage.hpp"
#include "workflow/run/run_dir.hpp"
#include "workflow/spreading/scene_model.hpp"
#include "workflow/stage/stage_settings.hpp"

namespace spreadmap {
namespace {

struct Override {
  SceneKey key;
  nlohmann::json value;  // SI
};

struct Fidelity {
  std::string name;
  std::vector<Override> overrides;
  nlohmann::json description = nlohmann::json::object();  // key -> value as written
};

// One fidelity's runs, one entry per heap: V_s, R_q, wall time and particle-steps.
struct HeapRuns {
  std::vector<double> vs, rq, wall, psteps;
};

using Stats = analysis::MeanSd;
const auto stats = analysis::mean_sd;

constexpr sm_param_v1 tradeoff_schema[] = {
    integer("heaps", 2, 100, 3, "heaps (seeds) run at each fidelity: their scatter is the yardstick"),
    table("fidelities", "a list of at least 2: {name: reference, time.safety: 0.2}, {name: default}, ... each a "
                        "name and the scene keys it changes"),
    table("render", "true, false or the figure's settings {width: 1920, vector: pdf}"),
};

class TradeoffStage : public Stage {
 public:
  void validate(const Workflow &wf, const StageEntry &entry, const Scene *scene, PluginRegistry &registry,
                Diagnostics &diag) override {
    const std::string file = wf.file.string();
    const YAML::Node &cfg = entry.config;
    if (scene && layered(*scene))
      diag.error(entry.where, "tradeoff", "measures one pass; a multi-layer scene is not supported yet",
                 "spread one layer on a plate in the tradeoff's workflow (scene.layers.count: 1, no scene.machine)");
    heaps_ = int(setting_count(entry.settings, "heaps"));
    style_ = figures::read_style(cfg["render"], false, false, file, "tradeoff.render", diag);
    render_ = style_.on;
    const YAML::Node list = cfg["fidelities"];
    if (!list || !list.IsSequence() || list.size() < 2) {
      diag.error(Location::of(file, list ? list : cfg), "tradeoff.fidelities", "needs a list of at least 2 fidelities",
                 "e.g. - {name: reference, time.safety: 0.2} and - {name: default}");
      return;
    }
    if (!scene) return;
    std::set<std::string> names;
    for (std::size_t i = 0; i < list.size(); ++i) {
      const YAML::Node f = list[i];
      const std::string where = fmt::format("tradeoff.fidelities[{}]", i);
      Fidelity fid;
      fid.name = f["name"] ? f["name"].as<std::string>() : fmt::format("f{}", i);
      if (!names.insert(fid.name).second)
        diag.error(Location::of(file, f), where + ".name", "'" + fid.name + "' is used twice",
                   "give each fidelity its own name");
      for (const auto &kv : f) {
        const std::string key = kv.first.as<std::string>();
        if (key == "name") continue;
        fid.description[key] = kv.second.as<std::string>();
        Override o;
        std::string why;
        if (!find_scene_key(*scene, registry, key, o.key, why)) {
          diag.error(Location::of(file, kv.first), where + "." + key, why);
          continue;
        }
        if (key == "precision") {
          const std::string v = kv.second.as<std::string>();
          if (v != "double" && v != "float")
            diag.error(Location::of(file, kv.second), where + ".precision", "'" + v + "' is not double or float");
          o.value = v;
        } else {
          o.value = validate_value(*o.key.param, kv.second, file, where + "." + key, diag);
        }
        fid.overrides.push_back(o);
      }
      fidelities_.push_back(std::move(fid));
    }
  }

  void run(StageContext &ctx) override {
    figures::use_style(style_);
    std::vector<HeapRuns> results;
    for (const auto &fidelity : fidelities_) results.push_back(run_heaps(ctx, fidelity));
    std::size_t ref = 0;
    for (std::size_t f = 1; f < results.size(); ++f)
      if (stats(results[f].psteps).mean > stats(results[ref].psteps).mean) ref = f;
    const Stats vs_ref = stats(results[ref].vs), rq_ref = stats(results[ref].rq);
    const double n = heaps_;

    analysis::Table table(
        {"fidelity", "settings", "heaps", "wall_seconds", "particle_steps", "vs", "vs_sd", "rq", "rq_sd",
         "vs_error_percent", "vs_error_in_scatter", "rq_error_percent", "rq_error_in_scatter"},
        "tradeoff.csv");
    std::vector<figures::TradeoffRow> figure_rows;
    std::string md = fmt::format(
        "| fidelity | settings | wall [s] | particle-steps | V_s [mm²/s] | R_q [µm] | V_s error | R_q error |\n"
        "|---|---|---|---|---|---|---|---|\n");
    for (std::size_t f = 0; f < results.size(); ++f) {
      const auto &r = results[f];
      const Stats vs = stats(r.vs), rq = stats(r.rq), wall = stats(r.wall), ps = stats(r.psteps);
      // the error of a mean against the reference's, in units of their combined standard error
      const double vs_err = 100 * (vs.mean - vs_ref.mean) / vs_ref.mean,
                   rq_err = 100 * (rq.mean - rq_ref.mean) / rq_ref.mean;
      const double vs_z = (vs.mean - vs_ref.mean) / std::sqrt((vs.sd * vs.sd + vs_ref.sd * vs_ref.sd) / n);
      const double rq_z = (rq.mean - rq_ref.mean) / std::sqrt((rq.sd * rq.sd + rq_ref.sd * rq_ref.sd) / n);
      const std::string settings =
          fidelities_[f].description.empty() ? "scene as given" : fidelities_[f].description.dump();
      table.add_row({fidelities_[f].name, settings, std::to_string(heaps_), analysis::Table::format(wall.mean),
                     analysis::Table::format(ps.mean), analysis::Table::format(vs.mean), analysis::Table::format(vs.sd),
                     analysis::Table::format(rq.mean), analysis::Table::format(rq.sd),
                     analysis::Table::format(f == ref ? 0 : vs_err), analysis::Table::format(f == ref ? 0 : vs_z),
                     analysis::Table::format(f == ref ? 0 : rq_err), analysis::Table::format(f == ref ? 0 : rq_z)});
      figure_rows.push_back({fidelities_[f].name, wall.mean, vs_err, rq_err, f == ref});
      md += fmt::format("| {}{} | `{}` | {:.1f} | {:.3g} | {:.3f} ± {:.3f} | {:.2f} ± {:.2f} | {} | {} |\n",
                        fidelities_[f].name, f == ref ? " (reference)" : "", settings, wall.mean, ps.mean,
                        vs.mean * 1e6, vs.sd * 1e6, rq.mean * 1e6, rq.sd * 1e6,
                        f == ref ? "–" : fmt::format("{:+.2f} % ({:+.1f} σ)", vs_err, vs_z),
                        f == ref ? "–" : fmt::format("{:+.2f} % ({:+.1f} σ)", rq_err, rq_z));
    }
    md += fmt::format(
        "\nMean ± sample standard deviation over {} heaps. Errors are against the reference's mean; σ is the "
        "combined standard error of the two means, sqrt((s_f² + s_ref²)/{}).\n",
        heaps_, heaps_);
    const fs::path dir = ctx.run.root() / "tradeoff";
    fs::create_directories(dir);
    table.write_csv((dir / "tradeoff.csv").string());
    write_atomic(dir / "tradeoff.md", md);
    figures::tradeoff(figure_rows, 100 * vs_ref.sd / vs_ref.mean, 100 * rq_ref.sd / rq_ref.mean, dir / "tradeoff.png");
    spdlog::info("tradeoff: {} fidelities x {} heaps; reference {}; {}", fidelities_.size(), heaps_,
                 fidelities_[ref].name, (dir / "tradeoff.md").string());
  }

 private:
  // The fidelity's case on each heap (seeds 1 to heaps_), run or read back, and measured.
  HeapRuns run_heaps(StageContext &ctx, const Fidelity &fidelity) const {
    HeapRuns r;
    for (int h = 1; h <= heaps_; ++h) {
      CaseRequest req;
      req.id = fmt::format("tradeoff_{}_heap{}", fidelity.name, h);
      req.scene = ctx.scene;
      for (const auto &o : fidelity.overrides) apply_scene_value(req.scene, o.key, o.value);
      req.scene.powder.seed = h;
      req.inputs = {{"fidelity", fidelity.name}, {"seed", h}};
      req.dir = ctx.run.case_dir(req.id);
      req.heaps = ctx.run.heaps();
      bool ran = false;
      const auto c = ensure_case(ctx, req, render_, ran, "tradeoff");
      const auto layer = measure_case_layer(ctx.registry, req.scene, req.dir);
      r.vs.push_back(layer.metrics.value("vs", std::nan("")));
      r.rq.push_back(layer.metrics.value("rq", std::nan("")));
      // wall time of the case as last measured: the manifest keeps it across resumed runs
      double wall = c.value("wall_seconds_last_run", std::nan(""));
      for (const auto &mc : ctx.run.manifest()["cases"])
        if (mc.value("id", "") == req.id && mc.contains("wall_seconds")) wall = mc["wall_seconds"];
      r.wall.push_back(wall);
      r.psteps.push_back(c.value("steps", 0.0) * 0.5 *
                         (c.value("particles_start", 0.0) + c.value("particles_end", 0.0)));
      spdlog::info("tradeoff: {} heap {}: V_s {:.4g} mm^2/s, R_q {:.4g} um, {:.1f} s{}", fidelity.name, h,
                   r.vs.back() * 1e6, r.rq.back() * 1e6, wall, ran ? "" : " (finished before)");
    }
    return r;
  }

  std::vector<Fidelity> fidelities_;
  int heaps_ = 0;  // from the settings (the schema default is 3)
  figures::Style style_;
  bool render_ = false;
};

}  // namespace

std::unique_ptr<Stage> make_tradeoff_stage() { return std::make_unique<TradeoffStage>(); }
SchemaView tradeoff_settings() { return {tradeoff_schema, std::size(tradeoff_schema)}; }

}  // namespace spreadmap
