// How the characterise stage measures a case, shared with the stages that measure their own cases
// the same way (verify): the stage's settings read from its workflow section (metrics plugin and
// parameters, sampling region, figures), and one finished case folder measured into metrics.json
// (+ heightmap.vti, heightmap.png), or its metrics.json reused while its key is unchanged.
#pragma once
#include <filesystem>
#include <nlohmann/json_fwd.hpp>
#include <string>

#include "core/diagnostics.hpp"
#include "core/registry.hpp"
#include "workflow/characterise/layer_eval.hpp"
#include "workflow/figures/figure_style.hpp"
#include "workflow/file/workflow.hpp"

namespace spreadmap {

struct CharacteriseSettings {
  LayerRequest request;  // plugin and its validated parameters; the region is `region`
  Region region;
  // region.y not written on a periodic strip: each case is measured across its own width (a cheap
  // fidelity's strip, a design over domain.width), not the workflow scene's.
  bool y_across_case = false;
  figures::Style style;
  bool render = true;
};

// The settings of a characterise section (`cfg` may be an empty map: the defaults). Errors name the
// workflow file and the key under "characterise.". `scene`: null when the scene has errors.
CharacteriseSettings read_characterise_settings(const Workflow &wf, const YAML::Node &cfg, const Scene *scene,
                                                PluginRegistry &registry, Diagnostics &diag);

// What decides a case's metrics besides its own inputs: plugin, parameters and region.
std::string settings_hash(const CharacteriseSettings &settings);

// The metrics document of the finished case in `dir` (id `id`) under `key` (settings_hash + the
// case's hash): its metrics.json when that holds the same key and !force, else measured now and
// written. `evaluated` tells which. `layer` k >= 1: layer k of a multi-layer case, in its layer_K
// folder (the key then names the layer too); 0: a single pass.
nlohmann::json case_metrics(PluginRegistry &registry, const CharacteriseSettings &settings,
                            const std::filesystem::path &dir, const std::string &id, const std::string &key, bool force,
                            bool &evaluated, int layer = 0);

}  // namespace spreadmap
