// Packing against depth (metrics/layer depth_profile) against closed forms of ideal lattices.
//
// Simple cubic lattice of touching spheres (spacing a = d): at height z the spheres' cross-sections
// cover pi (r^2 - (z - zc)^2) per cell area a^2, so a slice [z0, z1] within one sphere row has the
// solid fraction pi / (a^2 (z1 - z0)) [r^2 (z1 - z0) - ((z1 - zc)^3 - (z0 - zc)^3) / 3], and any whole
// number of rows pi / 6. Face-centred cubic lattice (cube side a, 4 spheres per cube, touching
// along the face diagonals: r = a sqrt(2) / 4): pi / (3 sqrt 2) = 0.74048 over whole cubes. In the
// interior of the lattice these hold exactly, wherever the region's walls cut spheres, as long as the
// region spans whole lattice cells.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "depth_profile.hpp"
#include "layer_metrics.hpp"

namespace {

namespace layer = spreadmap::layer;
constexpr double pi = std::numbers::pi;
constexpr double a = 100e-6;  // lattice spacing [m]
constexpr int cells = 6;      // the region is cells x cells lattice cells, the lattice cells high
const double region[4] = {0, cells *a, 0, cells *a};

struct Spheres {
  std::vector<double> x, y, z, r;
  void add(double xi, double yi, double zi, double ri) {
    x.push_back(xi), y.push_back(yi), z.push_back(zi), r.push_back(ri);
  }
  layer::SphereArrays arrays() const { return {x.size(), x.data(), y.data(), z.data(), r.data()}; }
};

// Simple cubic rows resting on z = 0, shifted by `shift` in x and y; one ring more outside the region
// so that the walls cut spheres wherever the shift puts them.
Spheres simple_cubic(double shift) {
  Spheres s;
  for (int i = -1; i <= cells; ++i)
    for (int j = -1; j <= cells; ++j)
      for (int k = 0; k < cells; ++k) s.add((i + 0.5) * a + shift, (j + 0.5) * a + shift, (k + 0.5) * a, a / 2);
  return s;
}

// Face-centred cubic, cubes resting on z = 0 (the bottom spheres' centres at z = r).
Spheres face_centred_cubic() {
  constexpr double basis[4][3] = {{0, 0, 0}, {0.5, 0.5, 0}, {0.5, 0, 0.5}, {0, 0.5, 0.5}};
  const double r = a * std::sqrt(2.0) / 4;
  Spheres s;
  for (int i = -1; i <= cells; ++i)
    for (int j = -1; j <= cells; ++j)
      for (int k = 0; k < cells; ++k)
        for (const auto &b : basis) s.add((i + b[0]) * a, (j + b[1]) * a, (k + b[2]) * a + r, r);
  return s;
}

// Closed-form solid fraction of the simple cubic slice [z0, z1] (z0, z1 above the substrate).
double simple_cubic_slice(double z0, double z1) {
  const double r = a / 2;
  double solid = 0;
  for (int k = 0; k < cells; ++k) {
    const double zc = (k + 0.5) * a, lo = std::max(z0, zc - r), hi = std::min(z1, zc + r);
    if (hi > lo) solid += r * r * (hi - lo) - (std::pow(hi - zc, 3) - std::pow(lo - zc, 3)) / 3;
  }
  return pi * solid / (a * a * (z1 - z0));
}

layer::DepthProfile profile(const Spheres &s, double slice, double mean_height, double top = 0) {
  return layer::depth_profile(s.arrays(), region, {}, 0.0, mean_height, {slice, top});
}

}  // namespace

// Slices of a quarter of the spacing, walls through the gaps between spheres (no sphere cut) and
// through sphere centres (halves and quarters cut by the walls): every slice as the closed form.
TEST(LayerDepthProfile, SimpleCubicSlicesMatchTheClosedForm) {
  for (const double shift : {0.0, a / 2}) {
    const auto p = profile(simple_cubic(shift), a / 4, cells * a);
    ASSERT_EQ(p.packing.size(), static_cast<std::size_t>(4 * cells)) << "shift " << shift;
    for (std::size_t i = 0; i < p.packing.size(); ++i) {
      EXPECT_NEAR(p.z[i], (i + 0.5) * a / 4, 1e-18);
      EXPECT_NEAR(p.packing[i], simple_cubic_slice(i * a / 4, (i + 1) * a / 4), 1e-12)
          << "slice " << i << ", shift " << shift;
    }
    // four quarters make one row: pi / 6
    for (std::size_t row = 0; row < cells; ++row) {
      double sum = 0;
      for (std::size_t q = 0; q < 4; ++q) sum += p.packing[4 * row + q];
      EXPECT_NEAR(sum / 4, pi / 6, 1e-12) << "row " << row;
    }
  }
}

// Walls cutting spheres off their centres. Spheres crossing an x wall, a y wall and a slice plane at
// once are approximated (the header says how), but in a lattice spanning whole cells the four corner
// pieces make one sphere and their errors cancel: rows and slices stay exact.
TEST(LayerDepthProfile, SimpleCubicCutOffCentreByTheWalls) {
  for (const double shift : {a / 3, a / 5, 0.1234 * a}) {
    const auto p = profile(simple_cubic(shift), a / 4, cells * a);
    ASSERT_EQ(p.packing.size(), static_cast<std::size_t>(4 * cells));
    for (std::size_t i = 0; i < p.packing.size(); ++i)
      EXPECT_NEAR(p.packing[i], simple_cubic_slice(i * a / 4, (i + 1) * a / 4), 1e-12) << "slice " << i;
  }
}

// One corner sphere alone (unit radius, centre (0.4, 0.6) from the corner's walls, slices of a
// quarter radius): against the volume integrated numerically over z and x (disk-quadrant chords),
// within 0.012 of the sphere's volume per slice (measured: 0.0111 at worst over centres -0.7..0.4 x
// -0.5..0.6 and slices from -0.8 to 0.55), and its slices add up to its volume in the prism exactly.
TEST(LayerDepthProfile, CornerSphereApproximationIsBounded) {
  const double cx = 0.4, cy = 0.6, sphere = 4 * pi / 3;
  const auto chord_area = [](double radius, double x_min,
                             double y_min) {  // disk of `radius` at 0, x >= x_min, y >= y_min
    constexpr int n = 4000;
    const double lo = std::max(x_min, -radius), h = (radius - lo) / n;
    double area = 0;
    for (int i = 0; i < n && h > 0; ++i) {
      const double x = lo + (i + 0.5) * h, top = std::sqrt(std::max(0.0, radius * radius - x * x));
      area += std::max(0.0, top - std::max(y_min, -top)) * h;
    }
    return area;
  };
  double total = 0;
  for (int k = 0; k < 8; ++k) {
    const double z0 = -1 + 0.25 * k, z1 = z0 + 0.25, box[6] = {0, 10, 0, 10, z0, z1};
    constexpr int n = 400;
    double exact = 0;
    for (int i = 0; i < n; ++i) {
      const double z = z0 + (i + 0.5) * (z1 - z0) / n;
      exact += chord_area(std::sqrt(std::max(0.0, 1 - z * z)), -cx, -cy) * (z1 - z0) / n;
    }
    const double approx = layer::sphere_volume_in_box(cx, cy, 0, 1, box);
    EXPECT_NEAR(approx, exact, 0.012 * sphere) << "slice " << z0 << ".." << z1;
    total += approx;
  }
  const double prism[6] = {0, 10, 0, 10, -2, 2};
  EXPECT_NEAR(total, layer::sphere_volume_in_box(cx, cy, 0, 1, prism), 1e-14);
}

TEST(LayerDepthProfile, FaceCentredCubicWholeCubes) {
  const Spheres s = face_centred_cubic();
  const auto p = profile(s, a / 2, cells * a);
  const double fcc = pi / (3 * std::sqrt(2.0));
  // the bottom and top cubes are not whole (the lattice ends there): the interior ones
  for (std::size_t cube = 1; cube + 1 < cells; ++cube)
    EXPECT_NEAR((p.packing[2 * cube] + p.packing[2 * cube + 1]) / 2, fcc, 1e-12) << "cube " << cube;
}

// The slices add up to the solid in the region, the profile ends at the highest top, and
// packing_top / packing_bulk are the fractions of the slabs [H - t, H] and [0, H - t].
TEST(LayerDepthProfile, SlicesAddUpAndTopAndBulkSlabs) {
  const Spheres s = simple_cubic(a / 3);
  const auto p = profile(s, 30e-6, cells * a, 2 * a);
  const double area = cells * a * cells * a;
  double sum = 0;
  for (double f : p.packing) sum += f * area * 30e-6;
  EXPECT_NEAR(sum, layer::solid_volume_in_region(s.arrays(), region, {}), 1e-12 * sum);
  EXPECT_EQ(p.packing.size(), 20u);            // 600 um / 30 um
  EXPECT_NEAR(p.packing_top, pi / 6, 1e-12);   // two whole rows
  EXPECT_NEAR(p.packing_bulk, pi / 6, 1e-12);  // four whole rows
  // top thickness 0: two mean diameters (= 2 a here)
  EXPECT_NEAR(profile(s, 30e-6, cells * a).top_thickness, 2 * a, 1e-18);
  // a top thickness above the mean height: the whole bed is the top, no bulk
  const auto thick = profile(s, 30e-6, 1.5 * a, 2 * a);
  EXPECT_NEAR(thick.packing_top, simple_cubic_slice(0, 1.5 * a), 1e-12);
  EXPECT_TRUE(std::isnan(thick.packing_bulk));
  EXPECT_TRUE(std::isnan(profile(s, 30e-6, 0.0).packing_top));  // no height: undefined
}

TEST(LayerDepthProfile, RefusesASliceThatIsNotPositive) {
  const Spheres s = simple_cubic(0);
  EXPECT_THROW(profile(s, 0.0, a), std::invalid_argument);
  EXPECT_THROW(profile(s, -1e-6, a), std::invalid_argument);
  EXPECT_THROW(profile(s, 1e-12, a), std::invalid_argument);  // 6e8 slices
  EXPECT_THROW(profile(s, a, a, -1e-6), std::invalid_argument);
}
