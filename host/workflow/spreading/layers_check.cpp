#include "workflow/spreading/layers_check.hpp"

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include "core/schema.hpp"
#include "workflow/spreading/powder_sizes.hpp"

namespace spreadmap {

double estimated_heap_height(const Scene &scene) {
  const Powder &p = scene.powder;
  const double solid = p.volume > 0 ? p.volume : double(p.count) * size_distribution(p).mean_sphere_volume();
  const double footprint = (p.heap_to - p.heap_from) * scene.domain.width;
  return footprint > 0 ? solid / (heap_packing_estimate * footprint) : 0.0;
}

void check_layers(const Scene &scene, const YAML::Node &user, const std::string &file, PluginRegistry &registry,
                  Diagnostics &diag) {
  const Layers &layers = scene.layers;
  if (layers.count <= 1 || scene.machine) return;  // a machine's layers: machine_check.hpp
  const YAML::Node section = user["layers"];
  auto where = [&](const char *key) {
    if (section && section.IsMap() && section[key]) return Location::of(file, section[key]);
    return Location::of(file, section ? section : user);
  };
  const auto schema = SchemaView::of(*registry.get("spreader", scene.spreader.use).descriptor);
  if (!schema.find("gap") || !scene.spreader.params.contains("gap")) {
    diag.error(
        where("count"), "scene.layers.count",
        fmt::format("the spreader '{}' has no gap: the platform's drop cannot be applied to it", scene.spreader.use),
        "use a spreader plugin with a gap parameter (spreadmap plugins spreader lists them) or set layers.count: 1");
    return;
  }
  const double gap = scene.spreader.params["gap"].get<double>();
  const double heap = estimated_heap_height(scene);
  const double needed = double(layers.count) * layers.thickness + gap + heap;
  if (needed > scene.domain.height)
    diag.error(where("thickness"), "scene.layers.thickness",
               fmt::format("{} layers of {:g} um, the gap ({:g} um) and the heap fed on top (about {:.3g} mm at a "
                           "packing of {:g}) need {:.3g} mm, more than the domain's height {:.3g} mm",
                           layers.count, layers.thickness * 1e6, gap * 1e6, heap * 1e3, heap_packing_estimate,
                           needed * 1e3, scene.domain.height * 1e3),
               fmt::format("make the domain taller (domain.height >= {:.3g} mm), or use fewer or thinner layers",
                           needed * 1e3));
}

}  // namespace spreadmap
