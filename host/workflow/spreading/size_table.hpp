// scene.powder.table as users give it, inline or as a CSV file, turned into SI rows; every problem
// names the file it is in (the scene's or the CSV's), the line, the key and the fix.
//
// A row is one diameter {diameter, fraction} or a size class {from, to, fraction} (a sieve class:
// what passed the sieve `to` and stayed on `from`). All rows of a table are of one kind, listed from
// the smallest size up, classes not overlapping. Sizes carry units ("20 um"); a CSV header may give
// a column's unit in brackets ("from [um]") for the bare numbers below it. Fractions are >= 0 and
// sum to 1 within table_sum_tolerance (then normalised); "8 %" or a header "fraction [%]" is 0.08.
//
//   from [um],to [um],fraction
//   15,20,0.08
//   20,25,0.14
#pragma once
#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "core/diagnostics.hpp"

namespace spreadmap {

inline constexpr double table_sum_tolerance = 0.01;

// Replaces powder["table"] (a list of rows, or a CSV file name relative to `scene_dir`) by its SI
// rows, [{diameter, fraction}, ...] or [{from, to, fraction}, ...]. `node` is the table as written
// in `scene_file` (for positions; may be undefined). Problems go to `diag`.
void resolve_size_table(nlohmann::json &powder, const YAML::Node &node, const std::string &scene_file,
                        const std::filesystem::path &scene_dir, Diagnostics &diag);

}  // namespace spreadmap
