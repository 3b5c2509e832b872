// scene.substrate.height_map: a measured substrate instead of the flat plate, the layer of fixed
// spheres of substrate.roughness with its tops on a surface read from a CSV file
// (workflow/spreading/height_map_file.hpp) instead of a random field.
//
//   file             the CSV, relative to the file that names it
//   sphere_diameter  the spheres' diameter and spacing [m]; 0 = the powder's D50 by volume
//
// The map is one tile of a periodic surface, repeated over a larger domain, and sampled at the
// spheres' centres (bilinear). Everything else (the mean plane the spreader's gap and the layer's
// heights are measured from, the first heap fed onto it, the checks) is substrate.roughness's
// (workflow/spreading/substrate_roughness.hpp).
#pragma once
#include "core/yaml_fwd.hpp"

#include <filesystem>
#include <nlohmann/json_fwd.hpp>
#include <string>

#include "core/diagnostics.hpp"
#include "powder/rough_substrate.hpp"
#include "workflow/spreading/scene_model.hpp"

namespace spreadmap {

// The validated section {file (absolute), digest, sphere_diameter} of `node` as written in `scene_file`;
// null with the problems in `diag`: its keys, a file that is not there, and every problem of the map
// itself (named in the CSV file, by line).
nlohmann::json resolve_height_map(const YAML::Node &node, const std::string &scene_file,
                                  const std::filesystem::path &scene_dir, Diagnostics &diag);

// The map of a resolved scene, read again. Throws InputError when the file is gone, changed since the
// scene was resolved (its digest), or no longer a valid map.
powder::HeightField height_map_of(const HeightMap &map);

}  // namespace spreadmap
