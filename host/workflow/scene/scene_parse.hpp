// Reading a scene file: every key checked against the host's schemas (below) and the contact
// plugin's, with units, ranges, did-you-mean and positions; all problems reported together.
#pragma once
#include <optional>

#include "core/registry.hpp"
#include "workflow/scene/scene_spec.hpp"

namespace spreadmap::scene {

// Problems go to diag; the value is complete only when diag stays empty.
std::optional<SceneFile> parse_scene(const fs::path &file, const YAML::Node &root, PluginRegistry &registry,
                                     Diagnostics &diag);

}  // namespace spreadmap::scene
