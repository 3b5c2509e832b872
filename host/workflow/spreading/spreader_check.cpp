#include "workflow/spreading/spreader_check.hpp"

#include <fmt/format.h>

#include <exception>
#include <yaml-cpp/yaml.h>

#include "core/warn_once.hpp"
#include "workflow/spreading/case_setup.hpp"
#include "workflow/scene/spreader_span.hpp"

namespace spreadmap {

void check_spreader_span(const Scene &scene, const YAML::Node &user, const std::string &file, PluginRegistry &registry,
                         Diagnostics &diag) {
  sm_spreader_description_v2 described{};
  try {
    described = describe_spreader(scene, registry, file);
  } catch (const std::exception &) {
    return;  // a spreader that cannot be bound is reported where it is bound
  }
  const auto shortfall = spreader_span_shortfall(described, make_domain(scene));
  if (!shortfall) return;
  if (!shortfall->periodic) {
    const std::string text = fmt::format("{}: scene.spreader: {}\n  {}", file, shortfall->what, shortfall->fix);
    warn_once(text);
    return;
  }
  const YAML::Node section = user["spreader"];
  const YAML::Node at = section && section.IsMap() ? (section["y_centre"] ? section["y_centre"]
                                                      : section["length"] ? section["length"]
                                                                          : section)
                                                   : user;
  diag.error(Location::of(file, at), "scene.spreader.y_centre", shortfall->what, shortfall->fix);
}

}  // namespace spreadmap
