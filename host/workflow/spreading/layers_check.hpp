// The checks of scene.layers that need the whole scene: the spreader must have a gap to raise, and
// the domain must be tall enough for every layer and the last heap fed on top of them.
#pragma once
#include <yaml-cpp/yaml.h>

#include <string>

#include "core/diagnostics.hpp"
#include "core/registry.hpp"
#include "workflow/spreading/scene_model.hpp"

namespace spreadmap {

// The packing fraction assumed for a settled heap when its height is estimated before anything
// runs: a loose packing (random close packing is about 0.64; cohesive powders pack looser).
inline constexpr double heap_packing_estimate = 0.5;

// The height of the settled heap, estimated from its solid volume spread over its footprint
// (heap_from..heap_to by the domain's width) at heap_packing_estimate [m].
double estimated_heap_height(const Scene &scene);

// Refuses, naming the file, the line and the key, a multi-layer scene whose spreader has no `gap`
// or whose domain cannot hold count x thickness + gap + the estimated heap height.
void check_layers(const Scene &scene, const YAML::Node &user, const std::string &file, PluginRegistry &registry,
                  Diagnostics &diag);

}  // namespace spreadmap
