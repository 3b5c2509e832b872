// The machine's powder before a pass (scene.machine, machine_layout.hpp): the feed's reservoir filled
// once, and the strokes before each layer.
#pragma once
#include <filesystem>
#include <functional>
#include <string>

#include "core/registry.hpp"
#include "engine/particle_set.hpp"
#include "workflow/spreading/scene_model.hpp"

namespace spreadmap {

// The reservoir filled as an operator fills it: the powder poured over the piston (at its starting
// depth) by more than the reservoir holds, settled by the powder's rule with the spreader at rest
// behind it, then levelled: every sphere whose centre stands above the plates (z > 0) is taken away.
// Throws InputError when the reservoir is left less than full, Interrupted on SIGINT/SIGTERM.
template <class Real>
engine::ParticleSet fill_reservoir(const Scene &scene, PluginRegistry &reg, const std::string &label,
                                   const std::filesystem::path &scene_file,
                                   const std::function<void(double)> &progress = {});

// The strokes before layer k = scene.machine->layer: the platform drops by the thickness and the
// piston rises by dosing x thickness at stroke_speed, the powder on them moving with them; then the
// powder settles (at least the strokes' time, at most that plus settle_time, until settle_speed), the
// spreader at rest behind the feed. Throws Interrupted on SIGINT/SIGTERM.
template <class Real>
engine::ParticleSet after_strokes(const Scene &scene, PluginRegistry &reg, const std::string &label,
                                  const std::filesystem::path &scene_file, const engine::ParticleSet &bed);

}  // namespace spreadmap
