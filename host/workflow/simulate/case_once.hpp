// One case run to completion before the caller goes on, and its layer measured: the building blocks of
// the stages that decide their next case from the last result (adaptive design, trade study).
#pragma once
#include <nlohmann/json_fwd.hpp>
#include <string>

#include "workflow/cases/case_runner.hpp"
#include "workflow/characterise/layer_eval.hpp"
#include "workflow/stage/stage.hpp"
#include "workflow/spreading/scene_model.hpp"

namespace spreadmap {

// Runs the case here, through the local executor (one case at a time: the next case depends on this
// one's result), unless its folder already holds a finished result for the same inputs (or --force);
// records it in the manifest's case list and draws its snapshot. Returns case.json. `ran` tells
// whether it was simulated now; `stage` names the progress line. Throws Interrupted after
// SIGINT/SIGTERM, and the case's failure.
nlohmann::json ensure_case(StageContext &ctx, const CaseRequest &req, bool render, bool &ran, const std::string &stage);

// The layer metrics of a finished case over the scene's default sampling region, with the
// metrics plugin's default parameters.
LayerResult measure_case_layer(PluginRegistry &registry, const Scene &scene, const fs::path &dir);

}  // namespace spreadmap
