#include "workflow/spreading/coarse_grain.hpp"

#include <cmath>
#include <string>
#include <nlohmann/json.hpp>

#include "core/schema.hpp"

namespace spreadmap {

Scene coarse_grained(const Scene &scene, PluginRegistry &registry) {
  const double k = scene.powder.coarse_grain;
  if (k == 1) return scene;
  Scene s = scene;
  Powder &powder = s.powder;
  for (double *length : {&powder.diameter, &powder.d10, &powder.d50, &powder.d90, &powder.standard_deviation,
                         &powder.d_min, &powder.d_max})
    *length *= k;
  if (powder.table.is_array())
    for (auto &row : powder.table)
      for (const char *key : {"diameter", "from", "to"})
        if (row.contains(key) && row[key].is_number()) row[key] = row[key].get<double>() * k;
  if (powder.volume <= 0) powder.count = std::max<long long>(1, std::llround(double(powder.count) / (k * k * k)));
  const SchemaView law = SchemaView::of(*registry.get("contact", s.contact.use).descriptor);
  for (nlohmann::json *params : {&s.contact.params, &s.substrate.law, &s.spreader.law})
    for (std::size_t i = 0; i < law.n; ++i) {
      const sm_param_v1 &p = law.params[i];
      if (p.type == SM_NUMBER && p.unit && std::string(p.unit) == "m" && params->contains(p.name) &&
          (*params)[p.name].is_number())
        (*params)[p.name] = (*params)[p.name].get<double>() * k;
    }
  return s;
}

}  // namespace spreadmap
