// From a scene file to a running engine::Simulation: the file read and checked (load_scene), the
// contact plugin bound once per law (particle-particle, then one per wall), the walls and particles
// added. The Simulation points into the bound laws and the cylinder geometries, which live beside it.
#pragma once
#include <deque>
#include <memory>

#include "core/registry.hpp"
#include "engine/simulation.hpp"
#include "workflow/scene_file/scene_particles.hpp"
#include "workflow/scene_file/scene_spec.hpp"

namespace spreadmap::scene_file {

struct LoadedScene {
  SceneFile scene;
  SceneParticles particles;
};

// Reads, checks and loads everything a run needs; throws InputError (all key problems of the file
// together, then the particles' problems) before anything runs. `validate` uses it as it is.
LoadedScene load_scene(const fs::path &file, PluginRegistry &registry);

// A plane wall whose motion starts later than time 0: its velocity is set at `start`.
struct DelayedMotion {
  std::size_t plane;  // index in the Simulation
  Vec velocity;
  double start;
};

struct SceneRun {
  PluginInstance pair;
  std::deque<PluginInstance> wall_laws;  // one per wall, in the file's order (stable addresses)
  std::deque<CylinderWall> cylinders;    // the geometries' `self`
  std::unique_ptr<engine::Simulation<double>> sim;
  std::vector<DelayedMotion> delayed;
};

std::unique_ptr<SceneRun> build_scene(const LoadedScene &loaded, PluginRegistry &registry);

}  // namespace spreadmap::scene_file
