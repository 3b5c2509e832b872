#include "workflow/train/train_config.hpp"

#include "core/schema.hpp"
#include "core/suggest.hpp"

namespace spreadmap {

namespace {
std::vector<std::string> names(const YAML::Node &n) {
  std::vector<std::string> out;
  if (n.IsSequence())
    for (const auto &v : n) out.push_back(v.as<std::string>());
  else if (n.IsScalar()) out.push_back(n.as<std::string>());
  return out;
}
}  // namespace

TrainConfig read_train_config(const Workflow &wf, const StageEntry &entry, PluginRegistry &registry,
                              Diagnostics &diag) {
  const std::string file = wf.file.string();
  const YAML::Node &cfg = entry.config;
  static const std::vector<std::string> keys = {"model", "params", "inputs", "outputs",
                                                "split", "folds",  "seed",   "render"};
  TrainConfig c;
  for (const auto &kv : cfg) {
    const std::string k = kv.first.as<std::string>();
    if (std::find(keys.begin(), keys.end(), k) == keys.end()) {
      const auto near = closest(k, keys);
      diag.error(Location::of(file, kv.first), "train." + k, "unknown key",
                 (near.empty() ? "" : "did you mean '" + near + "'? ") + "known: " + join(keys));
    }
  }
  const std::vector<std::string> models = cfg["model"] ? names(cfg["model"]) : std::vector<std::string>{"bpnn"};
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
  try {
    if (cfg["folds"]) c.folds = cfg["folds"].as<std::size_t>();
    if (cfg["seed"]) c.seed = cfg["seed"].as<std::uint64_t>();
  } catch (const YAML::Exception &) {
    diag.error(Location::of(file, cfg), "train", "folds and seed must be whole numbers");
  }
  if (cfg["split"]) {
    try {
      if (!cfg["split"].IsScalar()) throw std::invalid_argument("a split is one word, e.g. loo or kfold:5");
      c.validation = analysis::parse_validation(cfg["split"].as<std::string>(), c.folds);
    } catch (const std::exception &e) {
      diag.error(Location::of(file, cfg["split"]), "train.split", e.what(),
                 "auto (the default) chooses by size: holdout from " + std::to_string(analysis::holdout_from_rows) +
                     " cases, 5-fold from " + std::to_string(analysis::loo_below_rows) + ", leave-one-out below");
    }
  }
  c.style = figures::read_style(cfg["render"], true, false, file, "train.render", diag);
  c.render = c.style.on;
  if (c.folds < 2) diag.error(Location::of(file, cfg["folds"]), "train.folds", "needs at least 2 folds");
  return c;
}

}  // namespace spreadmap
