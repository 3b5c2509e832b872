// The pieces every scene of a spreading case is built from (case_setup.hpp, machine_setup.hpp): the
// shared domain, laws and settings, its walls (a plane, the spreader), the spreader's rest before its
// start, and the settling run.
#pragma once
#include <array>
#include <filesystem>
#include <functional>
#include <string>

#include "core/registry.hpp"
#include "engine/particle_set.hpp"
#include "workflow/scene/scene_build.hpp"
#include "workflow/spreading/scene_model.hpp"
#include "workflow/spreading/settle_rule.hpp"

namespace spreadmap {

// What every scene of a case shares: the domain, gravity, the laws and the engine's settings; no
// walls and no particles yet.
scene::LoadedScene case_scene(const Scene &spreading, const std::filesystem::path &scene_file);

scene::WallSpec plane_wall(const std::string &name, const std::string &key, const std::array<double, 3> &point,
                           const std::array<double, 3> &normal, const nlohmann::json &law);

// The scene's spreader as a wall; the plugin sees time t + time_offset (< 0: at rest at its start).
scene::WallSpec spreader_wall(const Scene &scene, PluginRegistry &reg, double time_offset);

// The spreader rests at its start for t < 0: while a heap settles it sees times before that.
double rest_shift(const Scene &scene);

// No sphere within a twentieth of the largest diameter of the spreader at rest.
double heap_clearance(const Scene &scene);

// The powder's own rule: at least 0.3 x settle_time, at most settle_time, until settle_fraction of its
// spheres are slower than settle_speed.
SettleRule powder_settle_rule(const Powder &powder);

// Runs a settling scene by `rule`; `label` names the case and `what` the powder in the log;
// `progress` gets the fraction of max_time done. Throws Interrupted on SIGINT/SIGTERM.
template <class Real>
engine::ParticleSet settle_scene(const scene::LoadedScene &settling, PluginRegistry &reg, const SettleRule &rule,
                                 const std::string &label, const std::string &what,
                                 const std::function<void(double)> &progress);

}  // namespace spreadmap
