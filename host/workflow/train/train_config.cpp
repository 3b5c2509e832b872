#include "workflow/train/train_config.hpp"

#include "core/schema.hpp"
#include "core/suggest.hpp"
#include "workflow/stage/plugin_needs.hpp"
#include "workflow/stage/stage_settings.hpp"
#include <yaml-cpp/yaml.h>

namespace spreadmap {

namespace {
std::vector<std::string> names(const YAML::Node &n) {
  std::vector<std::string> out;
  if (n.IsSequence())
    for (const auto &v : n) out.push_back(v.as<std::string>());
  else if (n.IsScalar()) out.push_back(n.as<std::string>());
  return out;
}
constexpr sm_param_v1 train_schema[] = {
    table("model", "a surrogate plugin or a list of them (default: every one installed, in name order)"),
    table("params", "the surrogate's parameters {...}, or one mapping per model {NAME: {...}, ...}"),
    table("inputs", "input columns (default: the design's variables)"),
    table("outputs", "output columns (default [vs, rq])"),
    text("split", "auto", "auto (by the number of cases: holdout, 5-fold or leave-one-out) | holdout | kfold:K | loo "
                          "| column:NAME"),
    integer("folds", 2, 1000, 5, "K of a plain split: kfold"),
    integer("seed", 0, 1e9, 1, "seed of the split"),
    table("render", "true, false or the figure's settings {width: 1920, vector: pdf}"),
};

}  // namespace

SchemaView train_settings() { return {train_schema, std::size(train_schema)}; }

TrainConfig read_train_config(const Workflow &wf, const StageEntry &entry, PluginRegistry &registry,
                              Diagnostics &diag) {
  const std::string file = wf.file.string();
  const YAML::Node &cfg = entry.config;
  TrainConfig c;
  const std::vector<std::string> models = cfg["model"] ? names(cfg["model"]) : every_surrogate(registry);
  if (models.empty())
    diag.error(Location::of(file, cfg), "train", "no surrogate plugin is installed to train",
               "install one (docs/plugins.md; spreadmap plugins --kind surrogate lists them)");
  const YAML::Node params = cfg["params"];
  for (const auto &m : models) {
    const LoadedPlugin *plugin = nullptr;
    try {
      plugin = &registry.get("surrogate", m);
    } catch (const std::exception &e) {
      diag.error(Location::of(file, cfg["model"] ? cfg["model"] : cfg), "train.model", e.what());
      continue;
    }
    YAML::Node mine;
    if (params && params.IsMap()) mine = models.size() > 1 ? params[m] : params;
    c.models.emplace_back(m, validate_params(SchemaView::of(*plugin->descriptor), mine, file,
                                             models.size() > 1 ? "train.params." + m : "train.params", diag));
  }
  if (cfg["inputs"]) c.inputs = names(cfg["inputs"]);
  if (cfg["outputs"]) c.outputs = names(cfg["outputs"]);
  c.folds = setting_count(entry.settings, "folds");
  c.seed = setting_count(entry.settings, "seed");
  if (cfg["split"] && cfg["split"].IsScalar()) {
    try {
      c.validation = analysis::parse_validation(setting_text(entry.settings, "split"), c.folds);
    } catch (const std::exception &e) {
      diag.error(Location::of(file, cfg["split"]), "train.split", e.what(),
                 "auto (the default) chooses by size: holdout from " + std::to_string(analysis::holdout_from_rows) +
                     " cases, 5-fold from " + std::to_string(analysis::loo_below_rows) + ", leave-one-out below");
    }
  }
  c.style = figures::read_style(cfg["render"], true, false, file, "train.render", diag);
  c.render = c.style.on;
  return c;
}

}  // namespace spreadmap
