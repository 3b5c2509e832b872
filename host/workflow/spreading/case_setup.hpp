// A workflow's spreading case as a scene (workflow/scene/scene_build.hpp builds and runs it):
// the settling scene (the heap between two temporary walls, the spreader at rest) and the spreading
// scene (the settled heap, the substrate plane z = 0 and the moving spreader) are scenes like any
// scene file's, with the spreader as a wall. The case runner and the benchmarks
// (bench/peer_scene_bench.cpp) build through here, so the benchmark times exactly what the
// simulate stage runs.
#pragma once
#include <filesystem>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "core/registry.hpp"
#include "engine/simulation.hpp"
#include "workflow/spreading/scene_model.hpp"
#include "workflow/scene/scene_build.hpp"

#include <spreadmap/geometry.hpp>

namespace spreadmap {

namespace fs = std::filesystem;

// The scene's spreader plugin bound to its parameters (the geometry alone, for its description and
// for keeping the heap clear of it). `scene_file`: the case's resolved scene (cases/cNNN/scene.json),
// named in the plugin's refusal.
PluginInstance bind_spreader(const Scene &scene, PluginRegistry &reg, const fs::path &scene_file);

// The scene's spreader as it describes itself (outline, travel, speed, gap), from a bound instance.
sm_spreader_description_v2 describe_spreader(const Scene &scene, PluginRegistry &reg, const fs::path &scene_file);

// As case.json records them (SI): the description's outline and extent along y, whether it turns,
// its travel, speed and gap; a pose's reference point, angle, velocity, omega and x extent.
nlohmann::json to_json(const sm_spreader_description_v2 &spreader);
nlohmann::json to_json(const sm_spreader_pose_v2 &pose);

engine::Domain make_domain(const Scene &scene);

// The spreading run as a scene: the settled heap, the substrate and the spreader from its start.
scene::LoadedScene spreading_scene(const Scene &spreading, const engine::ParticleSet &heap,
                                        const fs::path &scene_file);

// Particles inserted in front of (and under) the spreader and settled under gravity between two
// temporary walls, with the spreader at rest at its start. `label` names the case in the log;
// `progress` gets the fraction of the settling time done. Throws Interrupted on SIGINT/SIGTERM.
template <class Real>
engine::ParticleSet settle_heap(const Scene &scene, PluginRegistry &reg, const std::string &label,
                                const fs::path &scene_file, const std::function<void(double)> &progress = {});

// Layer k >= 2 of a multi-layer case, or the first layer on a rough substrate (`scene` is
// layer_scene(): its spreader raised; the bed: the layers below, or the substrate's spheres). The bed with
// the heap fed on it (layer_feed.hpp), less the heap's spheres within the insertion's clearance of
// the raised spreader at rest. Throws InputError when a sphere of the bed touches that spreader.
engine::ParticleSet fed_onto_bed(const Scene &scene, PluginRegistry &reg, const fs::path &scene_file,
                                 const engine::ParticleSet &bed, const engine::ParticleSet &heap);

// That fed bed settled under gravity on the substrate, the raised spreader at rest at its start, by
// the first heap's rule (at least 0.3 x settle_time, until the fastest sphere is slower than
// settle_speed). Throws Interrupted on SIGINT/SIGTERM.
template <class Real>
engine::ParticleSet settle_on_bed(const Scene &scene, PluginRegistry &reg, const std::string &label,
                                  const fs::path &scene_file, const engine::ParticleSet &fed,
                                  const std::function<void(double)> &progress = {});

// The spreading run built from spreading_scene(). The Simulation points into the plugins `built` keeps.
template <class Real> struct SpreadingRun {
  std::unique_ptr<scene::SceneRun<Real>> built;
  engine::Simulation<Real> &sim;
  const scene::BoundSpreader &spreader;
};
template <class Real>
std::unique_ptr<SpreadingRun<Real>> make_spreading_run(const Scene &scene, PluginRegistry &reg,
                                                       const engine::ParticleSet &heap, const fs::path &scene_file);

// Runs the spreading run to t_end as Simulation::run_until does; with scene.time.sleep, the region
// where particles may fall asleep follows the spreader (time.sleep_behind behind its trailing edge),
// moved at every callback (every `every` steps), and on a machine takes in the buried powder too
// (machine.sleep_depth, machine_layout.hpp). The case runner and the benchmarks run through here.
template <class Real>
bool run_spreading(engine::Simulation<Real> &sim, const scene::BoundSpreader &spreader, const Scene &spreading,
                   double t_end, const typename engine::Simulation<Real>::StepCallback &callback = {},
                   std::uint64_t every = 100);

}  // namespace spreadmap
