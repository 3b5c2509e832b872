// The spreading scene's check that its spreader spans the domain's width (scene/spreader_span.hpp
// says why a short one fails).
#pragma once
#include "core/yaml_fwd.hpp"

#include <string>

#include "core/diagnostics.hpp"
#include "core/registry.hpp"
#include "workflow/spreading/scene_model.hpp"

namespace spreadmap {

// validate's check of a workflow's scene: refuses a spreader short of a periodic width (file:line,
// scene.spreader.y_centre, the centred value as the fix) and warns of one short of an open width.
void check_spreader_span(const Scene &scene, const YAML::Node &user, const std::string &file, PluginRegistry &registry,
                         Diagnostics &diag);

}  // namespace spreadmap
