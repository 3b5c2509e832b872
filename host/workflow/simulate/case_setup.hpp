// How a case's simulations are built from its resolved scene (scene_model.hpp): the bound
// plugins, the domain, the engine settings, the settled heap and the spreading run's Simulation
// (heap + substrate plane + spreader geometry). The case runner and the peer-scene benchmark
// (bench/peer_scene_bench.cpp) both build through here, so the benchmark times exactly what the
// simulate stage runs.
#pragma once
#include <filesystem>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "core/registry.hpp"
#include "engine/simulation.hpp"
#include "workflow/scene/scene_model.hpp"

#include <spreadmap/geometry.hpp>

namespace spreadmap {

namespace fs = std::filesystem;

// The bound plugin instances of a case: the contact law three times (particle-particle,
// -substrate, -spreader) and the spreader geometry.
struct CasePlugins {
  PluginInstance pair, substrate, spreader_law, spreader;
  // `scene_file`: the case's resolved scene (cases/cNNN/scene.json), named in a plugin's refusal.
  CasePlugins(const Scene &scene, PluginRegistry &reg, const fs::path &scene_file);
  engine::ContactLaw law(const PluginInstance &i) const;
  const sm_spreader_ops_v2 &spreader_ops() const { return *spreader.ops<sm_spreader_ops_v2>(); }
  sm_spreader_description_v2 spreader_description() const;
  sm_spreader_pose_v2 spreader_pose(double t) const;
};

// The scene's spreader as it describes itself (outline, travel, speed, gap), from a bound instance.
sm_spreader_description_v2 describe_spreader(const Scene &scene, PluginRegistry &reg, const fs::path &scene_file);

// As case.json records them (SI): the description's outline and extent along y, whether it turns,
// its travel, speed and gap; a pose's reference point, angle, velocity, omega and x extent.
nlohmann::json to_json(const sm_spreader_description_v2 &spreader);
nlohmann::json to_json(const sm_spreader_pose_v2 &pose);

engine::Domain make_domain(const Scene &scene);
engine::Settings make_settings(const Scene &scene, double dt);

// Particles inserted in front of (and under) the spreader and settled under gravity between two
// temporary walls, with the spreader at rest at its start. `label` names the case in the log;
// `progress` gets the fraction of the settling time done. Throws Interrupted on SIGINT/SIGTERM.
template <class Real>
engine::ParticleSet settle_heap(const Scene &scene, PluginRegistry &reg, const std::string &label,
                                const fs::path &scene_file, const std::function<void(double)> &progress = {});

// The spreading run: the heap, the substrate plane z = 0 and the moving spreader. The plugins are
// kept beside the Simulation, which points into them.
template <class Real> struct SpreadingRun {
  CasePlugins plugins;
  engine::Simulation<Real> sim;
};
template <class Real>
std::unique_ptr<SpreadingRun<Real>> make_spreading_run(const Scene &scene, PluginRegistry &reg,
                                                       const engine::ParticleSet &heap, const fs::path &scene_file);

// Runs the spreading run to t_end as Simulation::run_until does; with scene.time.sleep, the region
// where particles may fall asleep follows the spreader (time.sleep_behind behind its trailing edge),
// moved at every callback (every `every` steps). The case runner and the benchmarks run through here.
template <class Real>
bool run_spreading(engine::Simulation<Real> &sim, const CasePlugins &plugins, const Scene &scene, double t_end,
                   const typename engine::Simulation<Real>::StepCallback &callback = {}, std::uint64_t every = 100);

}  // namespace spreadmap
