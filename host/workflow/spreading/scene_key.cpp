#include "workflow/spreading/scene_key.hpp"

#include <cmath>
#include <nlohmann/json.hpp>

namespace spreadmap {

void apply_scene_value(Scene &scene, const SceneKey &key, const nlohmann::json &given) {
  const nlohmann::json value = key.param && key.param->type == SM_INTEGER && given.is_number()
                                   ? nlohmann::json(static_cast<long>(std::llround(given.get<double>())))
                                   : given;
  if (key.section == "contact") {
    const nlohmann::json before = scene.contact.params.contains(key.key) ? scene.contact.params[key.key] : nullptr;
    for (nlohmann::json *law : {&scene.substrate.law, &scene.spreader.law})
      if (law->contains(key.key) && (*law)[key.key] == before) (*law)[key.key] = value;
    scene.contact.params[key.key] = value;
  } else if (key.section == "substrate") {
    scene.substrate.law[key.key] = value;
  } else if (key.section == "spreader") {
    (key.spreader_law ? scene.spreader.law : scene.spreader.params)[key.key] = value;
  } else {
    set_host_key(scene, key.section, key.key, value);
  }
}

}  // namespace spreadmap
