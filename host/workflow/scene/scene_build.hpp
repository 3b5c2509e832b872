// From a scene (a scene file, or a workflow's spreading case: workflow/spreading/case_setup.hpp) to
// a running engine::Simulation: the contact plugin bound once per law (particle-particle, then one
// per wall), the spreader plugins bound, the particles and the walls added, the step backend
// chosen. The Simulation points into the bound plugins and the cylinder and block geometries, which live
// beside it.
#pragma once
#include <deque>
#include <memory>

#include "core/registry.hpp"
#include "engine/simulation.hpp"
#include "workflow/scene/scene_particles.hpp"
#include "workflow/scene/scene_spec.hpp"

#include <spreadmap/geometry.hpp>

namespace spreadmap::scene {

struct LoadedScene {
  SceneFile scene;
  SceneParticles particles;
};

// Reads, checks and loads everything a run needs; throws InputError (all key problems of the file
// together, then the particles' problems) before anything runs. `validate` uses it as it is.
LoadedScene load_scene(const fs::path &file, PluginRegistry &registry);

// A plane wall's velocity set at a later time: a motion that starts after time 0, or stops.
struct DelayedMotion {
  std::size_t plane;  // index in the Simulation
  Vec velocity;
  double time;
};

// A bound spreader plugin: what it says of itself and where it is at a time.
struct BoundSpreader {
  const PluginInstance *instance = nullptr;
  double time_offset = 0;
  const sm_spreader_ops_v2 &ops() const { return *instance->ops<sm_spreader_ops_v2>(); }
  sm_spreader_description_v2 description() const;
  sm_spreader_pose_v2 pose(double t) const;  // at the scene's time t
};

template <class Real> struct SceneRun {
  PluginInstance pair;
  std::deque<PluginInstance> wall_laws;  // one per wall, in the file's order (stable addresses)
  std::deque<PluginInstance> spreader_plugins;
  std::deque<CylinderWall> cylinders;    // the geometries' `self`
  std::deque<BlockWall> blocks;          // the geometries' `self`
  std::vector<BoundSpreader> spreaders;  // the spreader walls, in the file's order
  std::unique_ptr<engine::Simulation<Real>> sim;
  std::vector<DelayedMotion> delayed;
};

template <class Real> std::unique_ptr<SceneRun<Real>> build_scene(const LoadedScene &loaded, PluginRegistry &registry);

}  // namespace spreadmap::scene
