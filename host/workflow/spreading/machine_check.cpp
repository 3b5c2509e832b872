#include "workflow/spreading/machine_check.hpp"

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include "core/schema.hpp"
#include "core/warn_once.hpp"
#include "workflow/spreading/case_setup.hpp"
#include "workflow/spreading/machine_layout.hpp"
#include "workflow/spreading/powder_sizes.hpp"

namespace spreadmap {

namespace {

// Random sequential addition fills about this fraction of the box the reservoir's powder is poured into.
constexpr double pour_packing = 0.35;

struct MachineKeys {
  const YAML::Node &user;
  const std::string &file;
  // The user's node of scene.SECTION.KEY, else the section's, else the scene's.
  Location at(const char *section, const char *key) const {
    const YAML::Node s = user[section];
    if (s && s.IsMap() && s[key]) return Location::of(file, s[key]);
    return Location::of(file, s ? s : user);
  }
};

// The spreader: a gap, at rest behind the feed, its trailing edge past the well when it stops.
void check_spreader_path(const Scene &scene, const MachineLayout &l, const MachineKeys &keys,
                         PluginRegistry &registry, Diagnostics &diag) {
  const auto schema = SchemaView::of(*registry.get("spreader", scene.spreader.use).descriptor);
  if (!schema.find("gap") || !scene.spreader.params.contains("gap")) {
    diag.error(keys.at("spreader", "use"), "scene.spreader.use",
               fmt::format("the spreader '{}' has no gap: a machine's layers are spread at a gap above its plates",
                           scene.spreader.use),
               "use a spreader plugin with a gap parameter (spreadmap plugins spreader lists them)");
    return;
  }
  const PluginInstance spreader = bind_spreader(scene, registry, keys.file);
  const scene::BoundSpreader bound{&spreader, 0.0};
  const auto described = bound.description();
  const double front = bound.pose(-1.0).x_max, tail = bound.pose(described.duration).x_min;
  if (front > l.reservoir_from)
    diag.error(keys.at("spreader", "start"), "scene.spreader.start",
               fmt::format("at its start the spreader reaches x = {:.3g} mm, over the reservoir (from {:.3g} mm)",
                           front * 1e3, l.reservoir_from * 1e3),
               fmt::format("start the spreader further back, or move scene.machine.reservoir_from to {:.3g} mm or more",
                           front * 1e3));
  if (tail < l.well_to)
    diag.error(keys.at("spreader", "travel"), "scene.spreader.travel",
               fmt::format("the spreader stops with its trailing edge at x = {:.3g} mm, before the well ends ({:.3g} "
                           "mm): part of the layer is never spread",
                           tail * 1e3, l.well_to * 1e3),
               "make the spreader's travel longer, so that it passes the lip into the overflow");
}

// The reservoir: deep enough for every layer's dosing, and room above it to pour it.
void check_reservoir(const Scene &scene, double dmax, const MachineKeys &keys, Diagnostics &diag) {
  const Machine &m = *scene.machine;
  const double rise = double(scene.layers.count) * m.dosing * scene.layers.thickness;
  if (rise > m.reservoir_depth - dmax)
    diag.error(keys.at("machine", "reservoir_depth"), "scene.machine.reservoir_depth",
               fmt::format("the piston rises {} x {:g} x {:g} um = {:.3g} mm over the layers; the reservoir holds "
                           "{:.3g} mm of powder, less one largest sphere ({:.3g} um) that stays in it: it cannot "
                           "supply the layers",
                           scene.layers.count, m.dosing, scene.layers.thickness * 1e6, rise * 1e3,
                           m.reservoir_depth * 1e3, dmax * 1e6),
               fmt::format("make reservoir_depth at least {:.3g} mm, or use fewer layers or a smaller dosing",
                           (rise + dmax) * 1e3));
  if (m.dosing < 1)
    warn_once(fmt::format("{}: scene.machine.dosing: {:g} is below 1: the piston lifts less powder than a layer "
                          "holds, and the layer cannot fill",
                          keys.file, m.dosing));
  const double pour_height = (reservoir_fill_packing / pour_packing - 1) * m.reservoir_depth + 2 * dmax;
  if (pour_height > scene.domain.height)
    diag.error(keys.at("domain", "height"), "scene.domain.height",
               fmt::format("the reservoir's powder is poured from up to about {:.3g} mm above the plates, higher "
                           "than the domain ({:.3g} mm)",
                           pour_height * 1e3, scene.domain.height * 1e3),
               fmt::format("make domain.height at least {:.3g} mm", pour_height * 1e3));
}

// Powder keys of the heap that a machine does not use, when the user wrote them.
void warn_unused_powder_keys(const MachineKeys &keys) {
  const YAML::Node powder = keys.user["powder"];
  if (!powder || !powder.IsMap()) return;
  for (const char *key : {"count", "volume", "heap_from", "heap_to", "heap_top"})
    if (powder[key])
      warn_once(fmt::format("{}: scene.powder.{} is not used with a machine: its reservoir is filled to the brim",
                            keys.file, key));
}

}  // namespace

void check_machine(const Scene &scene, const YAML::Node &user, const std::string &file, PluginRegistry &registry,
                   Diagnostics &diag) {
  if (!scene.machine) return;
  const MachineKeys keys{user, file};
  const Machine &m = *scene.machine;
  const MachineLayout l = machine_layout(scene);
  const double dmax = size_distribution(scene.powder).upper();
  if (!scene.domain.periodic_y || scene.domain.periodic_x)
    diag.error(keys.at("domain", scene.domain.periodic_x ? "periodic_x" : "periodic_y"), "scene.domain",
               "a machine's strip is periodic across (y) and open along the spreading direction (x): its well has no "
               "side walls yet, and the overflow lets the powder out",
               "set domain.periodic_y: true and domain.periodic_x: false");
  if (scene.substrate.roughness || scene.substrate.height_map)
    diag.error(keys.at("substrate", scene.substrate.roughness ? "roughness" : "height_map"), "scene.substrate",
               "a machine's platform is a flat block: a rough or measured substrate is not supported on it",
               "remove substrate.roughness and substrate.height_map, or remove scene.machine");
  if (m.well_length < dmax)
    diag.error(keys.at("machine", "well_length"), "scene.machine.well_length",
               fmt::format("the well ({:.3g} um) is narrower than the largest sphere ({:.3g} um)", m.well_length * 1e6,
                           dmax * 1e6),
               fmt::format("make well_length at least {:.3g} um", dmax * 1e6));
  if (scene.domain.length - l.overflow_from < 2 * dmax)
    diag.error(keys.at("domain", "length"), "scene.domain.length",
               fmt::format("the machine ends at x = {:.3g} mm (the lip), leaving {:.3g} mm of domain for the overflow, "
                           "less than two of the largest spheres",
                           l.overflow_from * 1e3, (scene.domain.length - l.overflow_from) * 1e3),
               fmt::format("make domain.length at least {:.3g} mm", (l.overflow_from + 2 * dmax) * 1e3));
  check_reservoir(scene, dmax, keys, diag);
  if (diag.empty()) check_spreader_path(scene, l, keys, registry, diag);
  warn_unused_powder_keys(keys);
  if (m.sleep_depth > 0 && !scene.time.sleep)
    warn_once(fmt::format("{}: scene.machine.sleep_depth does nothing without time.sleep: true", file));
}

}  // namespace spreadmap
