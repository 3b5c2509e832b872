// Which spheres belong to the layer: those resting on the substrate, directly or through a chain of
// touching spheres. A sphere thrown up by the spreader and still in flight when the state is taken
// (or a cluster of them) touches neither and is not part of the spread layer; counted, it puts a
// spike into the height map that dominates R_q (seen on the quick preset: R_q 187 um for one heap
// against 112 um for the next).
//
// Ground: the substrate plane, and the spheres flagged in `ground` (a rough substrate's spheres),
// which rest by definition.
// Touching: centre distance <= (r_i + r_j)(1 + tolerance), or bottom within tolerance x diameter of
// the substrate plane; spheres at rest overlap slightly, so tolerance only absorbs round-off and the
// settling jitter of the state (default 1 %). In a periodic strip across y the distance is the
// minimum image. Spheres are binned in x-y columns first, so the cost grows linearly with their number.
#pragma once
#include <cstdint>
#include <vector>

#include "heightmap.hpp"

namespace spreadmap::layer {

inline constexpr double resting_tolerance = 0.01;

// resting[i] = 1 when sphere i rests on the ground (possibly through others), else 0. `ground`: NULL,
// or 1 for each sphere that is ground itself.
std::vector<std::uint8_t> resting_spheres(const SphereArrays &spheres, double substrate_z, const PeriodicStrip &strip,
                                          double tolerance = resting_tolerance, const std::uint8_t *ground = nullptr);

}  // namespace spreadmap::layer
