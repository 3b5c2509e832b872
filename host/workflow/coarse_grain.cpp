#include "workflow/coarse_grain.hpp"

#include <cmath>
#include <string>

#include "core/schema.hpp"

namespace spreadmap {

nlohmann::json coarse_grained(const nlohmann::json &scene, PluginRegistry &registry) {
  const double k = scene["powder"].value("coarse_grain", 1.0);
  if (k == 1) return scene;
  nlohmann::json s = scene;
  auto &powder = s["powder"];
  powder["diameter"] = powder["diameter"].get<double>() * k;
  powder["d50"] = powder["d50"].get<double>() * k;
  if (powder.contains("table") && powder["table"].is_array())
    for (auto &row : powder["table"])
      if (row.contains("diameter") && row["diameter"].is_number()) row["diameter"] = row["diameter"].get<double>() * k;
  if (powder.value("volume", 0.0) <= 0)
    powder["count"] = std::max<long long>(1, std::llround(powder["count"].get<double>() / (k * k * k)));
  const SchemaView law = SchemaView::of(*registry.get("contact", s["contact"]["use"].get<std::string>()).descriptor);
  for (nlohmann::json *params : {&s["contact"]["params"], &s["substrate"]["law"], &s["spreader"]["law"]})
    for (std::size_t i = 0; i < law.n; ++i) {
      const sm_param_v1 &p = law.params[i];
      if (p.type == SM_NUMBER && p.unit && std::string(p.unit) == "m" && params->contains(p.name) &&
          (*params)[p.name].is_number())
        (*params)[p.name] = (*params)[p.name].get<double>() * k;
    }
  return s;
}

}  // namespace spreadmap
