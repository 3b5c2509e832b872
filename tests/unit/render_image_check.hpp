// PNG checks for the figure tests: size, distinct colours, colour counts and the mean absolute
// difference against a stored reference (rewritten when SPREADMAP_REGENERATE_REFERENCES=1).
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace spreadmap::render::testing {

struct Image {
  int width = 0, height = 0;
  std::vector<std::array<std::uint8_t, 3>> pixels;  // row-major, bottom row first (VTK order)
};

Image read_png(const std::filesystem::path& png);
std::size_t distinct_colours(const Image& im);
// Number of pixels within `tolerance` (per channel, 0..255) of `rgb`.
std::size_t count_colour(const Image& im, const std::array<int, 3>& rgb, int tolerance = 0);
// Mean over pixels and channels of |a - b| (0..255); the images must have the same size.
double mean_abs_difference(const Image& a, const Image& b);
bool regenerate_references();
std::filesystem::path reference_path(const std::string& name);  // tests/unit/data/render/<name>.png

}  // namespace spreadmap::render::testing
