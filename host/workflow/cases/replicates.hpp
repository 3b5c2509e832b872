// Replicates: each design point simulated with N independent heaps, so that the metrics carry the
// scatter of the random packing (their mean and standard deviation, characterise). Replicate 0 is
// the case as written (cases/c000, the scene's own seed: a run without replicates is unchanged);
// replicate r >= 1 runs in cases/c000_r<r> with a heap seed derived from the scene's seed and r.
// The seed does not depend on the design point: heaps are settled once per distinct heap and shared
// by every point of the design, so replicate r of every point spreads the same heap (common random
// numbers: differences between points are not blurred by packing noise, the scatter over r is).
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>

#include "core/diagnostics.hpp"
#include "workflow/spreading/scene_model.hpp"

#include "core/yaml_fwd.hpp"

namespace spreadmap {

constexpr std::size_t max_replicates = 20;

// `replicates:` of a stage (1..20, default 1); errors name the file, line and key path.
std::size_t read_replicates(const YAML::Node &node, const std::string &file, const std::string &key_path,
                            std::size_t fallback, Diagnostics &diag);

// The heap seed of replicate r: the scene's seed for r = 0, a mix of both (0..2^32-1) otherwise.
std::int64_t replicate_seed(std::int64_t scene_seed, std::size_t replicate);

// The scene of replicate r of a case (its heap seed changed, nothing else).
Scene replicate_scene(const Scene &scene, std::size_t replicate);

// c000 for replicate 0, c000_r1, c000_r2 ... for the others (`point`: the case id of the point).
std::string replicate_id(const std::string &point, std::size_t replicate);

}  // namespace spreadmap
