// The checks of the contact laws' cohesion that need the whole scene (the powder's sizes, the
// backend, sleeping): what the engine would refuse at a case's first step is refused by `validate`,
// naming the file, the line, the key and the fix (docs/cohesion.md).
#pragma once
#include "core/yaml_fwd.hpp"

#include <string>

#include "core/diagnostics.hpp"
#include "core/registry.hpp"
#include "workflow/spreading/scene_model.hpp"

namespace spreadmap {

// Refuses an attraction that leaves no stable time step for the smallest particles (SJKR softening
// that cancels the contact's stiffness, particle-particle or against the plate), and van der Waals
// attraction across a gap with backend cuda or time.sleep.
void check_cohesion(const Scene &scene, const YAML::Node &user, const std::string &file, PluginRegistry &registry,
                    Diagnostics &diag);

}  // namespace spreadmap
