// The angle of a granular slope measured from the final particle state, for calibration.
//
// Both fits read the top surface: in each bin the highest point (centre z + radius) of any sphere,
// so buried particles do not matter. A least-squares line through the surface over its flank gives
// the slope; the same fit repeated on independent parts of the surface (azimuthal sectors of a heap,
// slabs along a drum's axis) gives the spread, and the uncertainty is that spread over sqrt(parts).
//
// heap_angle: a conical heap on a plate (lifted cylinder or draw-down test). The surface height h in
// square columns two mean diameters wide (equal areas, so the maximum's upward bias is the same in
// every column and does not tilt the fit), against the column's distance rho from the heap's axis
// (the particles' centroid in x, y), per azimuthal sector; the flank is where 0.2 H <= h <= 0.8 H
// (H: the heap's height), which leaves out the rounded apex and the toe.
// bed_angle: the free surface of a bed in a rotating drum whose axis is along y: surface z(x) in bins
// of two mean diameters, per slab in y; the flank is the middle 60 % of the surface's x extent, which
// leaves out the curled ends at the drum wall.
#pragma once
#include <cstddef>
#include <vector>

#include "engine/particle_set.hpp"

namespace spreadmap::calibrate {

struct AngleFit {
  double angle_deg = 0;           // mean over the parts
  double spread_deg = 0;          // standard deviation over the parts
  double uncertainty_deg = 0;     // spread / sqrt(parts): the standard error of the mean
  std::vector<double> parts_deg;  // each part's angle
  std::size_t points = 0;         // surface bins in the fits, all parts together
};

// base_z: the plate's height [m]. sectors >= 3. Throws std::runtime_error when the state holds no
// heap (fewer than 3 flank bins in some sector): the message says how many particles and how high.
AngleFit heap_angle(const engine::ParticleSet &state, double base_z, int sectors = 8);

// slabs >= 1 (2 or more for an uncertainty).
AngleFit bed_angle(const engine::ParticleSet &state, int slabs = 4);

// Several fits of the same slope (a drum's surface at several times) as one: every part of every fit
// pooled, so the uncertainty is the pooled spread over sqrt(all parts).
AngleFit pooled(const std::vector<AngleFit> &fits);

}  // namespace spreadmap::calibrate
