// One pass of the spreader over a settled start: the spreading run with its checkpoints (every
// time.checkpoint_interval wall-clock seconds, and on SIGINT/SIGTERM), its snapshots and its record.
#pragma once
#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "core/registry.hpp"
#include "engine/particle_set.hpp"
#include "workflow/spreading/scene_model.hpp"

namespace spreadmap {

namespace fs = std::filesystem;

// What one pass of the spreader leaves: its end state and the record case.json keeps of it.
struct Pass {
  engine::ParticleSet state;
  nlohmann::json record;
};

// One pass of the spreader over `start` (settled), resumed from the checkpoint in `dir` when one of
// this `hash` is there; writes dir/state.vtp (and dir/series/ with snapshots). Empty when the
// checkpoint could not be resumed (it is removed: the caller starts the pass again). `name` names the
// pass in the log; `progress` gets the fraction of the pass done. Throws Interrupted on
// SIGINT/SIGTERM after saving the checkpoint.
template <class Real>
std::optional<Pass> spread_pass(const Scene &scene, PluginRegistry &reg, const engine::ParticleSet &start,
                                const fs::path &dir, const fs::path &scene_file, const std::string &hash,
                                const std::string &name, const std::function<void(double)> &progress);

}  // namespace spreadmap
