// scene.substrate.roughness: a rough substrate instead of the flat plate, made of fixed spheres on a
// Gaussian random height field (scene/rough_substrate.hpp) that span the domain over the plate.
//
//   rq                  R_q of the spheres' tops about their mean plane [m]
//   correlation_length  the field's correlation length xi [m], at least 2 sphere diameters
//   sphere_diameter     the spheres' diameter and spacing [m]; 0 = the powder's D50 by volume
//
// The substrate is drawn from the case's powder.seed (offset by a constant, so that it and the heap
// draw different numbers): replicates get different substrates, a rerun the same one. Its mean plane
// (the mean of the tops, mean_top) takes the flat plate's place as the plane the spreader's gap and
// the layer's heights are measured from (workflow/spreading/layer_feed.hpp).
#pragma once
#include <yaml-cpp/yaml.h>

#include <cstdint>
#include <optional>
#include <string>

#include "core/diagnostics.hpp"
#include "core/registry.hpp"
#include "powder/rough_substrate.hpp"
#include "workflow/spreading/scene_model.hpp"

namespace spreadmap {

// Above this many spheres the substrate is refused: the engine would spend its time on the substrate.
inline constexpr double max_substrate_spheres = 2e6;

// Whether the substrate is a layer of fixed spheres (roughness or height_map), not the flat plate.
bool has_substrate_spheres(const Scene &scene);

// The spheres' diameter: roughness's or height_map's sphere_diameter, or the powder's D50 by volume
// when that is 0 [m]. The scene must have substrate spheres.
// `scene` is the scene the engine runs (coarse graining applied, as cases/cNNN/scene.json keeps it).
double substrate_sphere_diameter(const Scene &scene);

// The substrate's seed: powder.seed offset by a constant.
std::uint64_t substrate_seed(const Scene &scene);

// The substrate of spheres of the scene the engine runs (rough or measured: height_map); empty for the
// flat plate. Deterministic: the same scene gives the same spheres. Throws std::invalid_argument as
// powder::rough_substrate does (a validated scene never does), InputError as height_map_of does.
std::optional<powder::RoughSubstrate> rough_substrate_of(const Scene &scene);

// The plane the spreader's gap and the layer's heights are measured from [m]: z = 0 for the flat plate,
// the rough substrate's mean plane (its mean_top) otherwise.
double substrate_level(const Scene &scene);

// The checks of substrate.roughness (or height_map, where they apply) that need the whole scene, each naming the file,
// the line and the key: a sphere diameter that fits the domain, a correlation length of at least 2 sphere diameters and
// not beyond the domain, a substrate of at most max_substrate_spheres spheres, peaks below the spreader's gap, a domain
// tall enough for the peaks, the further layers and the heap fed on top, and a backend that can run fixed spheres (not
// an explicit cuda).
void check_roughness(const Scene &scene, const YAML::Node &user, const std::string &file, PluginRegistry &registry,
                     Diagnostics &diag);

}  // namespace spreadmap
