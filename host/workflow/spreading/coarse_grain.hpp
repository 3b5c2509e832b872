// Coarse graining (scene.powder.coarse_grain = k >= 1): each sphere stands for k^3 of the powder's.
// Diameters grow by k (every length of the size distribution, every size of a table), the particle
// count falls by k^3 (rounded; a heap sized by volume keeps its volume), and every length parameter
// of the contact laws (unit m in their schema, e.g. hooke_slider's overlap_max) grows by k, so that
// contacts keep their overlap relative to the diameter and the time step grows with the contact
// time. Stiffnesses given directly (N/m, Pa) are left as they are. The gap, the domain and the spreader are the
// physical ones: that is what makes coarse graining a fidelity to measure, not a free saving.
#pragma once
#include "core/registry.hpp"
#include "workflow/spreading/scene_model.hpp"

namespace spreadmap {

// The scene with coarse graining applied (k = 1: unchanged), coarse_grain kept as given.
Scene coarse_grained(const Scene &scene, PluginRegistry &registry);

}  // namespace spreadmap
