#include "workflow/spreading/substrate_height_map.hpp"

#include <fmt/format.h>
#include <spreadmap/params.hpp>
#include <nlohmann/json.hpp>
#include <yaml-cpp/yaml.h>

#include "core/error.hpp"
#include "core/files.hpp"
#include "core/schema.hpp"
#include "workflow/spreading/height_map_file.hpp"

namespace spreadmap {
namespace sm = spreadmap;
namespace {

const std::string key = "scene.substrate.height_map";

constexpr sm_param_v1 height_map_params[] = {
    sm::text("file", "",
             "CSV of the measured surface: columns x, y, height on a regular grid, one tile of a periodic "
             "surface (relative to the file that names it)"),
    sm::number("sphere_diameter", "m", 0, 0.1, 0,
               "diameter (and spacing) of the substrate's fixed spheres; 0 = the powder's D50 by volume"),
};

}  // namespace

nlohmann::json resolve_height_map(const YAML::Node &node, const std::string &scene_file,
                                  const std::filesystem::path &scene_dir, Diagnostics &diag) {
  const std::size_t before = diag.errors().size();
  nlohmann::json out = validate_params({height_map_params, std::size(height_map_params)}, node, scene_file, key, diag);
  if (diag.errors().size() > before) return nullptr;
  const std::string name = out["file"].get<std::string>();
  const Location at = Location::of(scene_file, node.IsMap() && node["file"] ? node["file"] : node);
  if (name.empty()) {
    diag.error(at, key + ".file", "no file: the measured surface's CSV is required",
               "give file: surface.csv (columns x, y, height on a regular grid)");
    return nullptr;
  }
  const std::filesystem::path csv =
      std::filesystem::path(name).is_absolute() ? std::filesystem::path(name) : scene_dir / name;
  if (!std::filesystem::is_regular_file(csv)) {
    diag.error(at, key + ".file", fmt::format("no CSV file {}", csv.string()),
               "a height map's name is relative to the folder of the file that names it");
    return nullptr;
  }
  const std::string text = read_text(csv);
  if (!parse_height_map(text, csv, key, diag)) return nullptr;
  out["file"] = std::filesystem::absolute(csv).lexically_normal().string();
  out["digest"] = stable_hash(text);
  return out;
}

powder::HeightField height_map_of(const HeightMap &map) {
  if (!std::filesystem::is_regular_file(map.file))
    throw InputError(
        fmt::format("{}: the height map {} is gone; put it back, or validate and run the workflow "
                    "again in a new run directory",
                    key, map.file));
  const std::string text = read_text(map.file);
  if (stable_hash(text) != map.digest)
    throw InputError(
        fmt::format("{}: the height map {} changed since its scene was resolved (digest {}); "
                    "restore it, or run the workflow again: a changed map is a different scene",
                    key, map.file, map.digest));
  Diagnostics diag;
  auto field = parse_height_map(text, map.file, key, diag);
  diag.throw_if_any();
  return *field;
}

}  // namespace spreadmap
