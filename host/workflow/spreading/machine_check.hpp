// The checks of scene.machine that need the whole scene: a strip periodic across (the well has no
// side walls yet), a flat platform, a spreader with a gap that starts behind the feed and passes the
// well, a well wider than the largest sphere, a reservoir deep enough for every layer's dosing, room
// above the reservoir to pour it and beyond the lip for the overflow. A dosing factor below 1 is
// warned (the layer cannot fill); powder keys a machine does not use are warned when written.
#pragma once
#include "core/yaml_fwd.hpp"

#include <string>

#include "core/diagnostics.hpp"
#include "core/registry.hpp"
#include "workflow/spreading/scene_model.hpp"

namespace spreadmap {

void check_machine(const Scene &scene, const YAML::Node &user, const std::string &file, PluginRegistry &registry,
                   Diagnostics &diag);

}  // namespace spreadmap
