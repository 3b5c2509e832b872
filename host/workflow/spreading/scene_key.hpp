// A design variable: a key of the scene by the name users write (U, omega, gap, seed, precision) or
// a dotted path (contact.friction, powder.count, spreader.diameter), and the one function that sets
// it on a scene. The simulate stage's design, the adaptive design and the tradeoff stage's
// fidelities all change their scenes through apply_scene_value.
#pragma once
#include <nlohmann/json_fwd.hpp>
#include <spreadmap/abi.h>

#include <string>

#include "workflow/spreading/scene_model.hpp"

namespace spreadmap {

struct SceneKey {
  std::string name;                    // as written
  std::string section;                 // "" (top level), domain, powder, time, contact, substrate, spreader
  std::string key;                     // within the section (the plugin's parameter name)
  bool spreader_law = false;           // section spreader: the particle-spreader law, not the geometry
  const sm_param_v1 *param = nullptr;  // schema entry (type, unit, range)
};

// Sets `value` (SI; a number is rounded for an integer key) at `key`. contact.X changes the
// particle-particle law and the substrate and spreader laws that inherit its value (theirs equals
// it); a law with a value of its own keeps it.
void apply_scene_value(Scene &scene, const SceneKey &key, const nlohmann::json &value);

}  // namespace spreadmap
