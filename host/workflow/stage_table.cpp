#include "workflow/stage_table.hpp"

#include "core/diagnostics.hpp"
#include "workflow/stage/commands.hpp"
#include "workflow/stage/stage.hpp"
#include <nlohmann/json.hpp>
#include <yaml-cpp/yaml.h>

namespace spreadmap {

std::unique_ptr<Stage> make_calibrate_stage();
std::unique_ptr<Stage> make_simulate_stage();
std::unique_ptr<Stage> make_verify_stage();
std::unique_ptr<Stage> make_tradeoff_stage();
SchemaView calibrate_settings();
SchemaView simulate_settings();
SchemaView characterise_settings();
SchemaView train_settings();
SchemaView map_settings();
SchemaView verify_settings();
SchemaView tradeoff_settings();

const std::vector<StageInfo> &stage_table() {
  static const std::vector<StageInfo> table = {
      {"calibrate", "friction and rolling friction of the contact law from measured bulk angles (docs/calibration.md)",
       make_calibrate_stage, false, calibrate_settings(), nullptr, cmd_calibrate, "FILE",
       "friction and rolling friction from measured bulk angles (docs/calibration.md)", "calibration"},
      {"simulate", "the design's spreading cases: a settled heap spread at each setting, one case folder each",
       make_simulate_stage, true, simulate_settings(), nullptr, cmd_simulate, "SCENE",
       "run one explicit scene file (particles, walls, outputs; docs/scenes.md)", nullptr},
      {"characterise", "the layer metrics of every case (V_s, R_q, packing, coverage) into metrics.csv",
       [] { return make_characterise_stage(); }, true, characterise_settings(), "metrics", cmd_characterise, "STATE",
       "layer metrics of a particle file (.vtp or .csv)", "characterize"},
      {"train", "surrogate models fitted to metrics.csv, scored by cross-validation and the study's holdout",
       make_train_stage, false, train_settings(), nullptr, cmd_train, "TABLE", "fit a surrogate to a CSV table", nullptr},
      {"map", "the process map of a trained model and the optimum for each roughness target", make_map_stage, false,
       map_settings(), nullptr, cmd_map, "MODEL", "process map of a trained model", nullptr},
      {"verify", "simulates the map's optimum and checks the prediction against the runs", make_verify_stage, true,
       verify_settings(), nullptr, cmd_verify, "WORKFLOW",
       "simulate the optimum a workflow's map proposes and check it against the prediction", nullptr},
      {"tradeoff", "the cost and error of cheaper fidelities against the heap-to-heap scatter", make_tradeoff_stage,
       true, tradeoff_settings(), nullptr, nullptr, nullptr, nullptr, nullptr},
  };
  return table;
}

const StageInfo *find_stage(const std::string &name) {
  for (const auto &s : stage_table())
    if (name == s.name) return &s;
  return nullptr;
}

std::vector<std::string> stage_names() {
  std::vector<std::string> out;
  for (const auto &s : stage_table()) out.push_back(s.name);
  return out;
}

nlohmann::json check_stage_settings(const StageInfo &info, const YAML::Node &config, const std::string &file,
                                    Diagnostics &diag) {
  std::set<std::string> plugin_keys;  // the stage checks them against its plugin's schema
  if (info.plugin_settings && config.IsMap())
    for (const auto &kv : config)
      if (!info.settings.find(kv.first.as<std::string>())) plugin_keys.insert(kv.first.as<std::string>());
  nlohmann::json settings = validate_params(info.settings, config, file, info.name, diag, plugin_keys);
  // A refused value reads as its default (see stage_settings.hpp); tables stay null where refused.
  bool refused = false;
  for (auto it = settings.begin(); it != settings.end();) {
    const sm_param_v1 *p = info.settings.find(it.key());
    if (it->is_null() && p && p->type != SM_TABLE) {
      it = settings.erase(it);
      refused = true;
    } else {
      ++it;
    }
  }
  Diagnostics already_reported;  // a refused required key was named by the check above
  if (refused) fill_defaults(info.settings, settings, Location::of(file, config), info.name, already_reported);
  return settings;
}

}  // namespace spreadmap
