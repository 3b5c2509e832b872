#include "workflow/cases/replicates.hpp"

#include "core/schema.hpp"
#include <yaml-cpp/yaml.h>

namespace spreadmap {

std::size_t read_replicates(const YAML::Node &node, const std::string &file, const std::string &key_path,
                            std::size_t fallback, Diagnostics &diag) {
  return read_whole_number(node, file, key_path, 1, max_replicates, fallback, diag);
}

std::int64_t replicate_seed(std::int64_t scene_seed, std::size_t replicate) {
  if (replicate == 0) return scene_seed;
  // splitmix64 of (seed, replicate): neighbouring seeds and replicates land far apart
  std::uint64_t z = std::uint64_t(scene_seed) + 0x9e3779b97f4a7c15ULL * (std::uint64_t(replicate) + 1);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  z ^= z >> 31;
  return std::int64_t(z & 0xffffffffULL);  // the schema's range of powder.seed
}

Scene replicate_scene(const Scene &scene, std::size_t replicate) {
  Scene s = scene;
  s.powder.seed = replicate_seed(scene.powder.seed, replicate);
  return s;
}

std::string replicate_id(const std::string &point, std::size_t replicate) {
  return replicate == 0 ? point : point + "_r" + std::to_string(replicate);
}

}  // namespace spreadmap
