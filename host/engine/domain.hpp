// The simulated box: axis-aligned, each axis either periodic (wrapped, minimum image) or open
// (a particle whose centre leaves [lo, hi) is removed and counted).
#pragma once
#include <array>

namespace spreadmap::engine {

struct Domain {
  std::array<double, 3> lo{0, 0, 0};  // [m]
  std::array<double, 3> hi{1, 1, 1};  // [m]
  std::array<bool, 3> periodic{false, false, false};

  double length(int axis) const { return hi[axis] - lo[axis]; }
};

}  // namespace spreadmap::engine
