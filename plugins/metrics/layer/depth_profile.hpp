// Packing against depth: the solid fraction of a bed in horizontal slices of the sampling region.
//
// A slice is the box region x [z_lo, z_hi); its solid fraction is the sphere volume inside it (periodic
// images included) over its volume. Sphere volumes in a box are exact (clipped_sphere.hpp, whose two
// clipping axes are taken as the two the sphere crosses) unless a sphere crosses a vertical plane in
// x, one in y and a horizontal plane at once: such a corner sphere counts its volume in the vertical
// prism times the share of the whole sphere between the horizontal planes (off by at most 1.1 % of a
// sphere's volume per corner sphere and slice, measured; at most four per slice, and their errors
// cancel when the region spans whole cells of a lattice).
//
// The profile runs from the substrate up to the top of the highest sphere reaching into the region,
// in slices of `slice`: z[i] = (i + 1/2) slice above the substrate, packing[i] its solid fraction.
// With H the mean height of the height map and t the top thickness:
//   packing_top  = solid volume in [H - t, H] / (area (H - max(0, H - t)))   (the top t below the mean surface)
//   packing_bulk = solid volume in [0, H - t] / (area (H - t))               (the bed below it; undefined if H <= t)
// heights above the substrate. Undefined values are NaN.
#pragma once
#include <cstddef>
#include <vector>

#include "heightmap.hpp"

namespace spreadmap::layer {

struct DepthSettings {
  double slice = 50e-6;      // slice thickness [m], > 0
  double top_thickness = 0;  // t [m]; 0 = two mean sphere diameters
};

struct DepthProfile {
  double slice = 0, top_thickness = 0;  // as used [m]
  std::vector<double> z;                // slice centres above the substrate [m]
  std::vector<double> packing;          // solid fraction of each slice [-]
  double packing_top = 0, packing_bulk = 0;
};

// Volume of a sphere (centre xc, yc, zc, radius r) inside box = x0, x1, y0, y1, z0, z1 [m^3].
double sphere_volume_in_box(double xc, double yc, double zc, double r, const double box[6]);

// Sphere volume in region x [z0 + i dz, z0 + (i + 1) dz) for i < n, periodic images included [m^3].
std::vector<double> solid_volume_in_slices(const SphereArrays &spheres, const double region[4],
                                           const PeriodicStrip &strip, double z0, double dz, std::size_t n);

// The profile and packing_top / packing_bulk of the spheres over the substrate at substrate_z, with
// the height map's mean height `mean_height` above it. Throws std::invalid_argument for slice <= 0,
// a negative top thickness, or more than 10^6 slices.
DepthProfile depth_profile(const SphereArrays &spheres, const double region[4], const PeriodicStrip &strip,
                           double substrate_z, double mean_height, const DepthSettings &settings);

}  // namespace spreadmap::layer
