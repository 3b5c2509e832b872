// The simulations of the verify stage: `runs` runs of each proposed operating point, in
// <run>/verify/v0, v0_r1, ... Each run spreads a heap that no design case used (seeds of replicates
// max_replicates, max_replicates + 1, ...: the check is independent of the training data). Finished
// runs are never recomputed (a killed one resumes from its checkpoint, as the simulate stage's
// cases do), and each is measured as the workflow's characterise stage measures its cases.
#pragma once
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "workflow/characterise/case_metrics.hpp"
#include "workflow/stage.hpp"

namespace spreadmap {

struct VerifyPoint {
  std::string id;         // v0, v1, ...
  Scene scene;            // the workflow's scene at this point's inputs
  nlohmann::json inputs;  // {name: SI value}
};

// Per point, per run: its metrics document (metrics.json). Unfinished runs run here in --jobs threads.
std::vector<std::vector<nlohmann::json>> run_and_measure(StageContext &ctx, const std::vector<VerifyPoint> &points,
                                                         std::size_t runs, const CharacteriseSettings &settings);

}  // namespace spreadmap
