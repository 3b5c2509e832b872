// A rough substrate: a layer of fixed spheres on a rectangular lattice whose tops follow a Gaussian
// random height field with a given R_q and correlation length.
//
// The field has the Gaussian autocorrelation C(r) = R_q^2 exp(-r^2 / xi^2): xi, the correlation
// length, is the lag at which it falls to 1/e. It is white noise on the lattice convolved with the
// kernel exp(-2 r^2 / xi^2) (truncated at 3 xi; the kernel convolved with itself is a Gaussian
// falling to 1/e at xi, on the lattice too to 1e-4 as long as the spacing is <= xi / 2), then
// shifted to mean 0 and scaled to R_q exactly: the statistics of one field are the requested R_q
// and, within its sampling error, xi. Along a periodic y the noise wraps; elsewhere the field is the
// middle of a longer one, so its edges are no smoother than its middle. Random: spreadmap::Random
// (the same numbers on every platform for one seed).
//
// Scenes use it through `scene.substrate.roughness` (workflow/spreading/substrate_roughness.hpp): the
// spheres are fixed particles over the plate (so the case steps on the CPU; backend: cuda is
// refused), the first heap is fed onto them as a later layer's is fed onto the bed, the spreader's gap
// and the layer's heights are measured from mean_top (workflow/spreading/layer_feed.hpp), state.vtp
// keeps the spheres fixed (its "fixed" column) and the layer metrics take them as ground, not
// layer (sm_layer_input_v1::substrate).
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

namespace spreadmap::powder {

// Heights on nx x ny lattice points spaced dx, dy; row-major h[iy * nx + ix] [m].
struct HeightField {
  std::size_t nx = 0, ny = 0;
  double dx = 0, dy = 0;
  std::vector<double> h;
};

// Throws std::invalid_argument for an empty lattice, rq < 0, a correlation length below 2 spacings
// (the lattice cannot carry it) or non-finite values.
HeightField gaussian_height_field(std::size_t nx, std::size_t ny, double dx, double dy, double rq,
                                  double correlation_length, bool periodic_y, std::uint64_t seed);

struct RoughnessSpec {
  double rq = 0, correlation_length = 0;  // [m]
  double sphere_diameter = 0;             // [m], also the lattice's spacing along x
  double length = 0, width = 0;           // the substrate spans [0, length] x [0, width] [m]
  bool periodic_y = false;                // y spacing: width / floor(width / d), so the lattice wraps
  std::uint64_t seed = 0;
};

// The spheres (centres and radius, SI), lowest bottom on z = 0, their tops z_top = z + r following the
// field; mean_top is the mean of the tops, the rough surface's mean plane.
struct RoughSubstrate {
  HeightField field;
  std::vector<double> x, y, z;
  double radius = 0, mean_top = 0;
};

// Throws std::invalid_argument as gaussian_height_field, and for a sphere diameter that does not fit.
RoughSubstrate rough_substrate(const RoughnessSpec &spec);

// A measured surface sampled at a lattice's points ((ix + 1/2) dx, (iy + 1/2) dy): bilinear between the
// map's points, which sit at (i map.dx, j map.dy) from its first one. The map is one tile of a
// periodic surface (its last point is followed by its first, one spacing on): a domain larger than
// the map repeats it. Throws std::invalid_argument for a map of fewer than 2 x 2 points.
HeightField sampled_height_field(const HeightField &map, std::size_t nx, std::size_t ny, double dx, double dy);

// The substrate of spec's lattice (its rq, correlation_length and seed unused) with its tops on `map`,
// sampled by sampled_height_field. Throws std::invalid_argument as it and rough_substrate do.
RoughSubstrate measured_substrate(const HeightField &map, const RoughnessSpec &spec);

}  // namespace spreadmap::powder
