#include "workflow/spreading/substrate_roughness.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <nlohmann/json.hpp>
#include <yaml-cpp/yaml.h>

#include "core/schema.hpp"
#include "workflow/spreading/layers_check.hpp"
#include "workflow/spreading/powder_sizes.hpp"
#include "workflow/spreading/substrate_height_map.hpp"
#include "workflow/spreading/coarse_grain.hpp"

namespace spreadmap {

double substrate_sphere_diameter(const Scene &scene) {
  const Substrate &sub = scene.substrate;
  const double given = sub.roughness ? sub.roughness->sphere_diameter : sub.height_map.value().sphere_diameter;
  if (given > 0) return given;
  return size_distribution(scene.powder).quantile(0.5, powder::FractionBasis::volume);
}

std::uint64_t substrate_seed(const Scene &scene) {
  return static_cast<std::uint64_t>(scene.powder.seed) + 0x9e3779b97f4a7c15ull;  // wraps: a different stream
}

bool has_substrate_spheres(const Scene &scene) {
  return scene.substrate.roughness.has_value() || scene.substrate.height_map.has_value();
}

namespace {

// The lattice (and, for a rough substrate, the field's statistics and seed) of the scene's substrate.
powder::RoughnessSpec roughness_spec(const Scene &scene) {
  powder::RoughnessSpec spec;
  if (const auto &r = scene.substrate.roughness) {
    spec.rq = r->rq;
    spec.correlation_length = r->correlation_length;
  }
  spec.sphere_diameter = substrate_sphere_diameter(scene);
  spec.length = scene.domain.length;
  spec.width = scene.domain.width;
  spec.periodic_y = scene.domain.periodic_y;
  spec.seed = substrate_seed(scene);
  return spec;
}

double highest_top(const powder::RoughSubstrate &s) { return *std::max_element(s.z.begin(), s.z.end()) + s.radius; }

}  // namespace

std::optional<powder::RoughSubstrate> rough_substrate_of(const Scene &scene) {
  if (scene.substrate.height_map)
    return powder::measured_substrate(height_map_of(*scene.substrate.height_map), roughness_spec(scene));
  if (!scene.substrate.roughness) return std::nullopt;
  return powder::rough_substrate(roughness_spec(scene));
}

double substrate_level(const Scene &scene) {
  const auto substrate = rough_substrate_of(scene);
  return substrate ? substrate->mean_top : 0.0;
}

namespace {

// The user's substrate section (roughness or height_map): where a key of it was written, and its key path.
struct SubstrateSection {
  YAML::Node node;
  const std::string &file;
  std::string key;

  Location where(const char *k) const {
    if (node.IsMap() && node[k]) return Location::of(file, node[k]);
    return Location::of(file, node);
  }
};

// The lattice fits the domain: spheres smaller than it, a correlation length the lattice can carry and
// the domain can hold, and not too many spheres. False when one of these is reported.
bool substrate_lattice_fits(const Scene &scene, bool measured, const SubstrateSection &section, Diagnostics &diag) {
  const SpreadingBox &domain = scene.domain;
  const double d = substrate_sphere_diameter(scene);
  const bool given_diameter =
      measured ? scene.substrate.height_map->sphere_diameter > 0 : scene.substrate.roughness->sphere_diameter > 0;
  const std::string diameter =
      given_diameter ? fmt::format("{:g} um", d * 1e6) : fmt::format("{:g} um (the powder's D50 by volume)", d * 1e6);
  if (d > domain.length || d > domain.width) {
    diag.error(section.where("sphere_diameter"), section.key + ".sphere_diameter",
               fmt::format("the sphere diameter {} does not fit the domain ({:g} x {:g} mm)", diameter,
                           domain.length * 1e3, domain.width * 1e3),
               fmt::format("give sphere_diameter <= {:g} um", std::min(domain.length, domain.width) * 1e6));
    return false;
  }
  const double xi = measured ? 0.0 : scene.substrate.roughness->correlation_length;
  if (!measured && xi < 2 * d) {
    diag.error(section.where("correlation_length"), section.key + ".correlation_length",
               fmt::format("{:g} um is below 2 sphere diameters (2 x {}): the lattice of spheres cannot carry it",
                           xi * 1e6, diameter),
               fmt::format("give correlation_length >= {:g} um, or a smaller sphere_diameter", 2 * d * 1e6));
    return false;
  }
  if (!measured && xi > domain.length) {
    diag.error(section.where("correlation_length"), section.key + ".correlation_length",
               fmt::format("{:g} mm is longer than the domain ({:g} mm): the surface would be one slope", xi * 1e3,
                           domain.length * 1e3),
               fmt::format("give correlation_length <= {:g} mm", domain.length * 1e3));
    return false;
  }
  const double spheres = std::floor(domain.length / d) * std::floor(domain.width / d);
  if (spheres > max_substrate_spheres) {
    diag.error(section.where("sphere_diameter"), section.key + ".sphere_diameter",
               fmt::format("spheres of {} make a substrate of {:.3g} fixed spheres, more than {:g}", diameter, spheres,
                           max_substrate_spheres),
               "give a larger sphere_diameter or make the domain smaller");
    return false;
  }
  return true;
}

// Room above the substrate: its peaks below the spreader's gap, and the further layers and the heap
// fed on top within the domain's height.
void check_room_above_substrate(const Scene &scene, const powder::RoughSubstrate &substrate, bool measured,
                                const char *name, const SubstrateSection &section, Diagnostics &diag) {
  const SpreadingBox &domain = scene.domain;
  const double peak = highest_top(substrate), above_mean = peak - substrate.mean_top;
  const auto &gap = scene.spreader.params.contains("gap") ? scene.spreader.params["gap"] : nlohmann::json();
  if (!gap.is_number()) {
    diag.error(section.where("rq"), section.key,
               fmt::format("the spreader '{}' has no gap to hold above the substrate's mean plane", scene.spreader.use),
               fmt::format("use a spreader plugin with a gap parameter (spreadmap plugins spreader lists them) or "
                           "remove substrate.{}",
                           name));
    return;
  }
  if (above_mean >= gap.get<double>())
    diag.error(section.where(measured ? "file" : "rq"), section.key + (measured ? ".file" : ".rq"),
               fmt::format("the substrate's highest sphere reaches {:.3g} um above its mean plane, not below the "
                           "spreader's gap ({:g} um): the spreader would strike the substrate",
                           above_mean * 1e6, gap.get<double>() * 1e6),
               measured ? "give a larger spreader gap (or a map of smaller heights)"
                        : "use a smaller rq or a larger spreader gap");
  const double later_layers = double(scene.layers.count - 1) * scene.layers.thickness;
  const double heap = estimated_heap_height(scene), needed = peak + later_layers + heap;
  if (needed > domain.height)
    diag.error(section.where("rq"), section.key,
               fmt::format("the substrate's peaks ({:.3g} mm), {:.3g} mm of further layers and the heap fed on top "
                           "(about {:.3g} mm at a packing of {:g}) need {:.3g} mm, more than the domain's height "
                           "{:.3g} mm",
                           peak * 1e3, later_layers * 1e3, heap * 1e3, heap_packing_estimate, needed * 1e3,
                           domain.height * 1e3),
               fmt::format("make the domain taller (domain.height >= {:.3g} mm)", needed * 1e3));
}

}  // namespace

void check_roughness(const Scene &given, const YAML::Node &user, const std::string &file, PluginRegistry &registry,
                     Diagnostics &diag) {
  if (!has_substrate_spheres(given)) return;
  const bool measured = given.substrate.height_map.has_value();
  const char *const name = measured ? "height_map" : "roughness";
  const SubstrateSection section{user["substrate"][name], file, std::string("scene.substrate.") + name};
  if (given.backend == "cuda") {
    diag.error(Location::of(file, user["backend"] ? user["backend"] : section.node), "scene.backend",
               "backend: cuda cannot run a substrate of spheres: they are fixed particles, which step on the CPU only",
               fmt::format("set backend: auto or cpu, or remove substrate.{}", name));
    return;
  }
  const Scene scene = coarse_grained(given, registry);  // the sizes the engine runs
  if (!substrate_lattice_fits(scene, measured, section, diag)) return;
  powder::RoughSubstrate substrate;
  try {
    substrate = *rough_substrate_of(scene);
  } catch (const std::invalid_argument &e) {
    diag.error(section.where("correlation_length"), section.key, e.what(),
               "give a longer correlation_length or a smaller sphere_diameter");
    return;
  }
  check_room_above_substrate(scene, substrate, measured, name, section, diag);
}

}  // namespace spreadmap
