// The simulations of the verify stage: `runs` runs of each proposed operating point, in
// <run>/verify/v0, v0_r1, ... Each run spreads a heap that no design case used (seeds of replicates
// max_replicates + first_seed, + 1, ...: the check is independent of the training data; a later
// round of the verify loop starts after the seeds of the rounds before). Finished
// runs are never recomputed (a killed one resumes from its checkpoint, as the simulate stage's
// cases do), and each is measured as the workflow's characterise stage measures its cases.
#pragma once
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "workflow/characterise/case_metrics.hpp"
#include "workflow/stage/stage.hpp"
#include "workflow/spreading/scene_model.hpp"

namespace spreadmap {

struct VerifyPoint {
  std::string id;         // v0, v1, ...
  Scene scene;            // the workflow's scene at this point's inputs
  nlohmann::json inputs;  // {name: SI value}
};

// The scene of run r of a point whose runs start at seed index first_seed.
Scene verify_run_scene(const VerifyPoint &point, std::size_t first_seed, std::size_t r);

// Per point, per run: its metrics document (metrics.json). Unfinished runs run here in --jobs threads.
std::vector<std::vector<nlohmann::json>> run_and_measure(StageContext &ctx, const std::vector<VerifyPoint> &points,
                                                         std::size_t runs, std::size_t first_seed,
                                                         const CharacteriseSettings &settings);

}  // namespace spreadmap
