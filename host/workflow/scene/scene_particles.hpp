// The particles of a scene file: read from its CSV or generated, then checked before anything runs
// (inside the domain, on the particles' side of every wall, no overlap beyond the tolerance).
#pragma once
#include <vector>

#include "engine/particle_set.hpp"
#include "workflow/scene/scene_spec.hpp"

namespace spreadmap::scene {

struct SceneParticles {
  engine::ParticleSet set;         // masses filled in
  std::vector<std::size_t> lines;  // CSV line of each particle; empty when generated
};

// Throws InputError naming the file, line and column (CSV) or the key (generate).
SceneParticles load_particles(const SceneFile &scene);

// Throws InputError listing the first problems (each with the particle's line and the fix).
void check_particles(const SceneFile &scene, const SceneParticles &particles);

}  // namespace spreadmap::scene
