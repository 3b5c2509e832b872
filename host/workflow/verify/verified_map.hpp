// map.png again once the optimum is checked: the same map as the map stage drew (its grid read back
// from map.csv, its targets from optimum.json), the optimum marked verified or not verified.
#pragma once
#include <nlohmann/json_fwd.hpp>

#include "analysis/model_file.hpp"
#include "workflow/stage/stage.hpp"

namespace spreadmap {

// verified: 1 when the first target's optimum was simulated inside its interval, 0 when not.
void redraw_verified_map(StageContext &ctx, const analysis::ModelFile &model, const nlohmann::json &optimum,
                         int verified);

}  // namespace spreadmap
