// The volume and mass of a sphere, for the host's engine, scene and workflow alike. Host-side
// helpers, header-only like size_sample.hpp. Each keeps one order of operations: a result's last bits
// depend on it, and the particles' masses and the heaps' volumes are compared bit for bit.
#pragma once
#include <cmath>
#include <numbers>

namespace spreadmap {

inline constexpr double sphere_volume_factor = std::numbers::pi / 6.0;  // V = (pi/6) d^3

// The volume of a sphere of diameter d: (pi/6) d^3.
constexpr double sphere_volume(double d) { return sphere_volume_factor * d * d * d; }

// The mass of a sphere of this density and radius: density 4/3 pi r^3.
inline double sphere_mass(double density, double radius) {
  return density * 4.0 / 3.0 * std::numbers::pi * std::pow(radius, 3);
}

}  // namespace spreadmap
