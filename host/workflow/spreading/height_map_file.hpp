// A measured surface as users give it (scene.substrate.height_map.file): a CSV of points on a
// regular grid, one row a point, the columns x, y and height. Units as in a size table: a header
// gives a column's unit in brackets ("height [um]") for the bare numbers below it, a cell may carry
// its own ("12.5 um"), bare numbers under a bare header are SI (m). Lines starting with # are comments.
//
//   x [um],y [um],height [um]
//   0,0,1.8
//   10,0,-0.6
//
// The points may come in any order; together they must fill an nx x ny grid (at least 2 x 2) with
// equal spacings along x and along y (within grid_tolerance of a spacing), each point once. The
// map is one tile of a periodic surface: the substrate repeats it over a larger domain
// (scene/rough_substrate.hpp, sampled_height_field).
#pragma once
#include <filesystem>
#include <optional>
#include <string>

#include "core/diagnostics.hpp"
#include "powder/rough_substrate.hpp"

namespace spreadmap {

inline constexpr double grid_tolerance = 1e-3;  // of a spacing
inline constexpr double height_map_max_points = 4e6;

// The grid of the CSV text `text`, read from the file `csv` (heights in m, h[iy * nx + ix] from the
// smallest x and y); nullopt with every problem reported to `diag` as file:line, `key` and the fix.
// The caller reads the file once and may hash the same text (substrate_height_map.hpp).
std::optional<powder::HeightField> parse_height_map(const std::string &text, const std::filesystem::path &csv,
                                                   const std::string &key, Diagnostics &diag);

}  // namespace spreadmap
