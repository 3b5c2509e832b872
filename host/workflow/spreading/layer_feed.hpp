// Spreading layer upon layer (scene.layers). The platform's drop is modelled by raising the
// spreader instead: for layer k the spreader's gap grows by (k - 1) x thickness while the substrate
// and the bed stay where they are. Gravity is uniform and the domain is open upwards to its height,
// so the two are the same motion seen from frames that differ by a translation along z, and
// raising the spreader keeps every particle inside the domain (z >= 0) without moving the bed.
// The heights of layer k are measured from z = (k - 1) x thickness, the lowered platform's place
// in the spreader's frame: layer k's mean height is the powder above the plane the spreader sees as
// the plate of the first layer.
//
// A rough substrate (scene.substrate.roughness) is the bed of the first layer: its fixed spheres stand
// on the plate (which stays below, so that fines cannot fall through), the first heap is fed onto
// them as later heaps are fed onto the layers below, and its mean plane (substrate_level(), the mean
// of the spheres' tops) takes the plate's place: the spreader is raised by it, and the heights are
// measured from it.
#pragma once
#include <functional>

#include "engine/particle_set.hpp"
#include "workflow/spreading/scene_model.hpp"

namespace spreadmap {

// How far the platform has dropped before layer k (1-based) is spread [m]: (k - 1) x thickness.
double platform_drop(const Scene &scene, int layer);

// The scene of layer k: the spreader's gap raised by the substrate's mean plane (0 for the flat
// plate, workflow/spreading/substrate_roughness.hpp) and platform_drop(scene, k). Layer 1's on the flat
// plate is `scene`. A machine's (scene.machine) keeps its spreader and puts its platform and piston in
// layer k's places instead (machine_layout.hpp).
Scene layer_scene(const Scene &scene, int layer);

// The rough substrate's spheres, fixed, numbered from 0: the bed the first heap is fed onto. Empty for
// the flat plate. `scene` is the scene the engine runs.
engine::ParticleSet substrate_spheres(const Scene &scene);

// The bed with a new heap of the same powder on it: the heap, as settled on the plate, lifted so
// that its lowest sphere clears the highest sphere of the bed under its footprint by `clearance`,
// appended after the bed, less the spheres `excluded(x, y, z, r)` refuses where they land (as the
// heap's insertion keeps clear of the spreader). The bed's spheres keep their identities; the new
// ones follow the bed's largest.
engine::ParticleSet feed_heap(const engine::ParticleSet &bed, const engine::ParticleSet &heap, double clearance,
                              const std::function<bool(double, double, double, double)> &excluded = {});

}  // namespace spreadmap
