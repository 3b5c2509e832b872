// Powder heap insertion: random sequential addition of non-overlapping spheres in a box.
//
// Spheres are drawn from a size distribution, sorted largest first (small ones then fill the
// gaps), and each is tried at uniformly random centres until it overlaps neither a placed sphere
// nor an exclusion shape (a cell grid of the largest diameter makes each check O(1), the whole
// insertion O(N)). Every sphere lies entirely inside the region, except along a periodic y where
// centres fill [y0, y1) and overlaps use the minimum image. Exclusion shapes are tested at the
// centre as drawn in [y0, y1), without periodic images (give shapes that span the strip, as a
// spreader spanning a periodic strip does, or that lie well inside it).
//
// When a sphere fails `attempts_per_sphere` consecutive tries the region is considered full: the
// top z1 is raised by one largest diameter (the base and the sides never move) and the sphere is
// tried again, up to `max_top`; past that, insert_heap throws PowderError with the numbers.
// Random sequential addition jams near a solid fraction of 0.38 (monodisperse); expect growth
// well before that. Deterministic: the same spec and seed give the same heap on every platform.
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <limits>
#include <vector>

#include "powder/powder_error.hpp"
#include "powder/size_distribution.hpp"

namespace spreadmap::powder {

struct Box {
  std::array<double, 3> lo, hi;  // [m]
};

// A solid cylinder with its axis along y at (x, z), spanning y in [y_lo, y_hi] (unbounded by
// default), e.g. a cylindrical body plus a clearance.
struct CylinderY {
  double x, z, radius;
  double y_lo = -std::numeric_limits<double>::infinity(), y_hi = std::numeric_limits<double>::infinity();
};

struct HeapSpec {
  Box region;                 // x0..x1, y0..y1, z0..z1 (z1 may grow, see above) [m]
  bool periodic_y = false;    // y0..y1 is a periodic strip
  std::size_t count = 0;      // give count or solid_volume (exactly one non-zero)
  double solid_volume = 0.0;  // powder volume (sum of sphere volumes) [m^3]
  SizeDistribution sizes;
  std::uint64_t seed = 1;
  std::vector<CylinderY> excluded_cylinders;  // no part of a sphere may lie inside these
  std::vector<Box> excluded_boxes;
  // Optional extra exclusion: returns true when a sphere (centre x, y, z, radius r) is not allowed.
  std::function<bool(double x, double y, double z, double r)> excluded;
  std::size_t attempts_per_sphere = 20000;                   // consecutive failures that mean "full"
  double max_top = std::numeric_limits<double>::infinity();  // highest z1 the region may grow to [m]
};

struct Heap {
  std::vector<double> x, y, z, r;  // centres and radii [m], largest spheres first
  double top = 0.0;                // final z1 of the region (> the requested one if it grew) [m]
  double solid_volume = 0.0;       // sum of sphere volumes [m^3]
  std::uint64_t attempts = 0;      // candidate positions tried
  std::size_t size() const { return r.size(); }
};

// Throws PowderError (inconsistent spec, or the spheres do not fit even after growing).
Heap insert_heap(const HeapSpec &spec);

// Number of particles whose expected total volume is `solid_volume` (rounded to nearest, >= 1).
// insert_heap uses it when the spec gives a volume; the actual volume then scatters around the
// target by sampling (exact for a monodisperse powder).
std::size_t heap_volume_to_count(double solid_volume, const SizeDistribution &sizes);

}  // namespace spreadmap::powder
