// map: the process map of a trained model (by default the train stage's first) into map/.
#include <spdlog/spdlog.h>

#include <algorithm>

#include "analysis/table.hpp"
#include "core/error.hpp"
#include "core/suggest.hpp"
#include "core/units.hpp"
#include "workflow/map/mapping.hpp"
#include "workflow/figures/figure_style.hpp"
#include "workflow/stage.hpp"
#include "workflow/train/train_config.hpp"

namespace spreadmap {
namespace {

class MapStage : public Stage {
 public:
  void validate(const Workflow &wf, const StageEntry &entry, const Scene *, PluginRegistry &registry,
                Diagnostics &diag) override {
    const std::string file = wf.file.string();
    const YAML::Node &cfg = entry.config;
    for (const auto &kv : cfg) {
      const std::string k = kv.first.as<std::string>();
      if (k != "model" && k != "grid" && k != "rq_max" && k != "render")
        diag.error(Location::of(file, kv.first), "map." + k, "unknown key", "known: model, grid, rq_max, render");
    }
    std::vector<std::string> trained;  // by this workflow's train stage, when it has one
    for (const auto &s : wf.stages)
      if (s.kind == "train") {
        Diagnostics ignore;  // the train stage reports its own problems
        for (const auto &m : read_train_config(wf, s, registry, ignore).models) trained.push_back(m.first);
      }
    if (!trained.empty()) model_ = trained.front();
    if (cfg["model"]) {
      model_ = cfg["model"].as<std::string>();
      if (!trained.empty() && std::find(trained.begin(), trained.end(), model_) == trained.end()) {
        const std::string near = closest(model_, trained);
        diag.error(Location::of(file, cfg["model"]), "map.model", "'" + model_ + "' is not trained by this workflow",
                   (near.empty() ? "" : "did you mean '" + near + "'? ") + "the train stage trains: " + join(trained));
      }
    }
    if (model_.empty()) model_ = "bpnn";
    grid_ = cfg["grid"] ? cfg["grid"].as<std::string>() : "";
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
    style_ = figures::read_style(cfg["render"], true, false, file, "map.render", diag);
    render_ = style_.on;
  }

  void run(StageContext &ctx) override {
    figures::use_style(style_);
    const fs::path model_json = ctx.run.train_dir(model_) / "model.json";
    if (!fs::exists(model_json))
      throw InputError("error: map: " + model_json.string() + " does not exist; run the train stage with model " +
                       model_);
    const auto file = analysis::load_model_json(model_json.string());
    MapRequest rq;
    if (!grid_.empty()) rq.points = parse_grid_points(grid_, mapped_inputs(file));
    rq.rq_max = rq_max_;
    const auto map = make_process_map(ctx.registry, file, rq);
    std::unique_ptr<analysis::Table> data;
    const fs::path data_csv = ctx.run.train_dir(model_) / "data.csv";
    if (fs::exists(data_csv)) data = std::make_unique<analysis::Table>(analysis::Table::read_csv(data_csv.string()));
    write_process_map(map, file, ctx.run.map_dir(), data.get(), render_);
    for (const auto &o : map.optima) {
      if (!o.found) {
        spdlog::warn("map: no setting on the grid reaches R_q <= {}", display(o.rq_max, "m"));
        continue;
      }
      std::string at;
      for (std::size_t i = 0; i < file.inputs.size(); ++i)
        at += (i ? ", " : "") + file.inputs[i].name + " = " + display(o.x(Eigen::Index(i)), file.inputs[i].unit);
      spdlog::info("map: for R_q <= {}: {} gives V_s = {}, R_q = {}", display(o.rq_max, "m"), at,
                   display(o.vs, "m^2/s"), display(o.rq, "m"));
    }
    spdlog::info("map: {} grid points in {}", map.grid.x.rows(), (ctx.run.map_dir() / "map.csv").string());
  }

 private:
  std::string model_, grid_;
  std::vector<double> rq_max_;
  figures::Style style_;
  bool render_ = true;
};

}  // namespace

std::unique_ptr<Stage> make_map_stage() { return std::make_unique<MapStage>(); }

}  // namespace spreadmap
