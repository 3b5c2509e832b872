// map: the process map of a trained model (by default the train stage's first) into map/, with the
// optimum for each roughness target chosen at a stated confidence (default 0.9).
#include <spdlog/spdlog.h>

#include <algorithm>
#include <nlohmann/json.hpp>
#include <yaml-cpp/yaml.h>

#include "analysis/table.hpp"
#include "core/error.hpp"
#include "core/suggest.hpp"
#include "core/units.hpp"
#include "workflow/stage/plugin_needs.hpp"
#include "workflow/map/mapping.hpp"
#include "workflow/figures/figure_style.hpp"
#include "workflow/stage/stage.hpp"
#include "workflow/run/run_dir.hpp"
#include "workflow/spreading/scene_model.hpp"
#include "workflow/stage/stage_settings.hpp"
#include "workflow/train/train_config.hpp"

namespace spreadmap {
namespace {

constexpr sm_param_v1 map_schema[] = {
    text("model", "", "the trained surrogate to map (default: the train stage's first)"),
    text("grid", "", "points per input, e.g. 41x41 (default 41 per mapped input)"),
    table("rq_max", "roughness targets: one or a list, e.g. [100 um, 110 um]; each gets an optimum"),
    number("confidence", "-", 0.5, 1, default_confidence,
           "the wanted P(R_q <= target) of the optimum, in [0.5, 1); 0.5 chooses by the predicted mean"),
    table("render", "true, false or the figure's settings {width: 1920, vector: pdf}"),
};

class MapStage : public Stage {
 public:
  void validate(const Workflow &wf, const StageEntry &entry, const Scene *, PluginRegistry &registry,
                Diagnostics &diag) override {
    const std::string file = wf.file.string();
    const YAML::Node &cfg = entry.config;
    const nlohmann::json &set = entry.settings;
    std::vector<std::string> trained;  // by this workflow's train stage, when it has one
    for (const auto &s : wf.stages)
      if (s.kind == "train") {
        Diagnostics ignore;  // the train stage reports its own problems
        for (const auto &m : read_train_config(wf, s, registry, ignore).models) trained.push_back(m.first);
      }
    if (!trained.empty()) model_ = trained.front();
    if (setting_text(set, "model") != "") {
      model_ = setting_text(set, "model");
      if (!trained.empty() && std::find(trained.begin(), trained.end(), model_) == trained.end()) {
        const std::string near = closest(model_, trained);
        diag.error(Location::of(file, cfg["model"]), "map.model", "'" + model_ + "' is not trained by this workflow",
                   (near.empty() ? "" : "did you mean '" + near + "'? ") + "the train stage trains: " + join(trained));
      }
    }
    if (model_.empty()) {  // no train stage in this workflow: the train stage's default, the first installed
      try {
        model_ = first_surrogate(registry, "the map stage");
      } catch (const Error &e) {
        diag.error(Location::of(file, cfg), "map.model", e.what());
      }
    }
    grid_ = setting_text(set, "grid");
    if (!grid_.empty()) {
      try {
        parse_grid_points(grid_, 2);
      } catch (const std::exception &e) {
        diag.error(Location::of(file, cfg["grid"]), "map.grid", e.what());
      }
    }
    if (const YAML::Node r = cfg["rq_max"]) {
      std::vector<YAML::Node> items;
      if (r.IsSequence())
        for (const auto &v : r) items.push_back(v);
      else items.push_back(r);
      for (const auto &v : items) {
        try {
          rq_max_.push_back(parse_in(v.as<std::string>(), "m"));
        } catch (const std::exception &e) {
          diag.error(Location::of(file, v), "map.rq_max", e.what(), "a roughness with its unit, e.g. 110 um");
        }
      }
    }
    confidence_ = setting_number(set, "confidence");
    if (confidence_ == 1)
      diag.error(Location::of(file, cfg["confidence"]), "map.confidence",
                 "P(R_q <= target) = 1 asks for an infinite margin on the prediction",
                 "the wanted P(R_q <= target) of the optimum, in [0.5, 1), e.g. 0.9");
    style_ = figures::read_style(cfg["render"], true, false, file, "map.render", diag);
    render_ = style_.on;
  }

  void run(StageContext &ctx) override {
    figures::use_style(style_);
    const fs::path model_json = ctx.run.train_dir(model_) / "model.json";
    if (!fs::exists(model_json))
      throw InputError("map: " + model_json.string() + " does not exist; run the train stage with model " +
                       model_);
    const auto file = analysis::load_model_json(model_json.string());
    MapRequest rq;
    if (!grid_.empty()) rq.points = parse_grid_points(grid_, mapped_inputs(file));
    rq.rq_max = rq_max_;
    rq.confidence = confidence_;
    const auto map = make_process_map(ctx.registry, file, rq);
    std::unique_ptr<analysis::Table> data;
    const fs::path data_csv = ctx.run.train_dir(model_) / "data.csv";
    if (fs::exists(data_csv)) data = std::make_unique<analysis::Table>(analysis::Table::read_csv(data_csv.string()));
    write_process_map(map, file, ctx.run.map_dir(), data.get(), render_);
    for (const auto &t : map.trust)
      if (t.untrusted()) spdlog::warn("map: the {} map is NOT TRUSTED: {}", t.output, t.reason);
    const auto untrusted = map.untrusted_basis();
    for (const auto &o : map.optima) {
      if (!o.found) {
        spdlog::warn("map: no setting on the grid reaches R_q <= {} with probability {:.2f}", display(o.rq_max, "m"),
                     o.confidence);
        continue;
      }
      spdlog::info("map: for R_q <= {} (confidence {:.2f}): {}", display(o.rq_max, "m"), o.confidence,
                   describe_optimum(o, file));
      if (!untrusted.empty())
        spdlog::warn("map: that optimum rests on an untrusted map ({}): simulate more cases or replicates before "
                     "setting a machine by it",
                     join(untrusted));
    }
    spdlog::info("map: {} grid points in {}", map.grid.x.rows(), (ctx.run.map_dir() / "map.csv").string());
  }

 private:
  std::string model_, grid_;
  std::vector<double> rq_max_;
  double confidence_ = default_confidence;
  figures::Style style_;
  bool render_ = true;
};

}  // namespace

std::unique_ptr<Stage> make_map_stage() { return std::make_unique<MapStage>(); }
SchemaView map_settings() { return {map_schema, std::size(map_schema)}; }

}  // namespace spreadmap
