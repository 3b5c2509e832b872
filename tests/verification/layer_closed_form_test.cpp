// Layer metrics against closed forms of ideal monolayers of touching spheres resting on the substrate.
//
// Over one lattice cell, h = r + sqrt(r^2 - rho^2) on each disk (rho: distance to the centre), 0 off it.
// Per sphere: integral of h over its disk = pi r^3 + 2 pi r^3 / 3 = 5 pi r^3 / 3, and of h^2 =
// pi r^4 (1 + 4/3 + 1/2) = 17 pi r^4 / 6. Dividing by the area per sphere A gives <h> and <h^2>, and
// R_q = sqrt(<h^2> - <h>^2). Square packing: A = 4 r^2, so <h> = 5 pi r / 12 and
// R_q = r sqrt(17 pi / 24 - 25 pi^2 / 144). Hexagonal packing: A = 2 sqrt(3) r^2.
//
// Sampling a jump (h falls from r to 0 at the disk's edge) at points counts lattice points in a disk:
// the error is O(cell / d) and, when the grid is aligned with the lattice, every lattice cell repeats
// the same count, so it oscillates with the cell (d/50 aligned: R_q off by 0.8 %; d/100: 0.1 %). A
// lattice at a generic angle samples every phase and is already within 0.02 % at d/50.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "layer_metrics.hpp"

namespace {

namespace layer = spreadmap::layer;
constexpr double pi = std::numbers::pi;
constexpr double r = 125e-6, d = 2 * r;
constexpr double within = 0.005;  // the requirement: 0.5 % of the closed form

struct Layer {
  std::vector<double> x, y, z, r;
  void add(double xi, double yi) {
    x.push_back(xi);
    y.push_back(yi);
    z.push_back(::r);  // resting on the substrate at z = 0
    r.push_back(::r);
  }
  layer::LayerResult characterise(double x0, double x1, double y0, double y1, double cell, double strip_lo = 0,
                                  double strip_hi = 0) const {
    sm_layer_input_v1 in{};
    in.n = x.size();
    in.x = x.data();
    in.y = y.data();
    in.z = z.data();
    in.r = r.data();
    in.region[0] = x0;
    in.region[1] = x1;
    in.region[2] = y0;
    in.region[3] = y1;
    in.periodic_y[0] = strip_lo;
    in.periodic_y[1] = strip_hi;
    in.speed = in.gap = std::numeric_limits<double>::quiet_NaN();
    return layer::characterise_layer(in, cell);
  }
};

const double square_mean = 5 * pi / 12 * r;
const double square_rq = r * std::sqrt(17 * pi / 24 - 25 * pi * pi / 144);

// Square packing on [0, 2 r m]^2 with centres at odd multiples of r (one ring more outside).
Layer square_lattice(int m) {
  Layer l;
  for (int i = -1; i <= m; ++i)
    for (int j = -1; j <= m; ++j) l.add((2 * i + 1) * r, (2 * j + 1) * r);
  return l;
}

TEST(LayerClosedForm, SquareMonolayerOnAFineGrid) {
  const int m = 4;
  const auto res = square_lattice(m).characterise(0, 2 * r * m, 0, 2 * r * m, d / 100);
  EXPECT_NEAR(res.metrics.mean_height, square_mean, within * square_mean);
  EXPECT_NEAR(res.metrics.rq, square_rq, within * square_rq);
  EXPECT_NEAR(res.metrics.coverage, pi / 4, within * pi / 4);
  // Solid: one sphere per 4 r^2 (the boundary spheres are cut through their centres), exactly.
  EXPECT_NEAR(res.metrics.solid_thickness, pi * r / 3, 1e-12 * r);
  EXPECT_EQ(res.metrics.particles_in_region, 16u);
  // The interstice between four touching disks, (4 - pi) r^2, isolated (disks touch at points); point
  // counting misplaces at most the points within half a diagonal of its boundary (perimeter pi r).
  const double interstice = (4 - pi) * r * r, slack = pi * r * (d / 100) * std::sqrt(0.5);
  EXPECT_NEAR(res.metrics.largest_bare_patch, interstice, slack);
}

TEST(LayerClosedForm, SquareMonolayerConvergesAsTheGridIsRefined) {
  const int m = 2;
  const Layer l = square_lattice(m);
  double previous_mean = 1, previous_rq = 1;
  for (int per_diameter : {10, 50, 200}) {
    const auto res = l.characterise(0, 2 * r * m, 0, 2 * r * m, d / per_diameter);
    const double mean_error = std::abs(res.metrics.mean_height / square_mean - 1);
    const double rq_error = std::abs(res.metrics.rq / square_rq - 1);
    EXPECT_LT(mean_error, previous_mean) << "d/" << per_diameter;
    EXPECT_LT(rq_error, previous_rq) << "d/" << per_diameter;
    previous_mean = mean_error;
    previous_rq = rq_error;
  }
  EXPECT_LT(previous_mean, 0.001);  // d/200
  EXPECT_LT(previous_rq, 0.001);
}

TEST(LayerClosedForm, SquareMonolayerAtAGenericAngleOnAD50Grid) {
  const double angle = 0.3, c = std::cos(angle), s = std::sin(angle), side = 20 * d;
  Layer l;
  for (int i = -25; i <= 25; ++i)
    for (int j = -25; j <= 25; ++j) {
      const double u = i * d, v = j * d;
      l.add(side / 2 + c * u - s * v, side / 2 + s * u + c * v);
    }
  const auto res = l.characterise(0, side, 0, side, d / 50);
  EXPECT_NEAR(res.metrics.mean_height, square_mean, within * square_mean);
  EXPECT_NEAR(res.metrics.rq, square_rq, within * square_rq);
}

TEST(LayerClosedForm, HexagonalMonolayerInAPeriodicStrip) {
  // Rows sqrt(3) r apart, alternate rows shifted by r; the strip holds 6 rows (3 rectangular cells
  // 2 r x 2 sqrt(3) r), its images fill the rest. Rows are incommensurate with the grid.
  const double row = std::sqrt(3.0) * r, strip = 6 * row, width = 10 * d;
  Layer l;
  for (int j = 0; j < 6; ++j)
    for (int i = -1; i <= 11; ++i) l.add(i * d + (j % 2 ? r : 0.0), (j + 0.5) * row);
  const auto res = l.characterise(0, width, 0, strip, d / 100, 0, strip);
  const double area_per_sphere = 2 * std::sqrt(3.0) * r * r;
  const double mean = 5 * pi * r * r * r / 3 / area_per_sphere, second = 17 * pi * std::pow(r, 4) / 6 / area_per_sphere;
  const double rq = std::sqrt(second - mean * mean);
  EXPECT_NEAR(res.metrics.mean_height, mean, within * mean);
  EXPECT_NEAR(res.metrics.rq, rq, within * rq);
  EXPECT_NEAR(res.metrics.coverage, pi * r * r / area_per_sphere, within * pi * r * r / area_per_sphere);
  // Exactly 60 spheres' worth of solid in the strip x width (row ends cut by the x planes).
  EXPECT_NEAR(res.metrics.solid_thickness, 4 * pi / 3 * r * r * r / area_per_sphere, 1e-12 * r);
}

TEST(LayerClosedForm, SingleSphere) {
  const double side = 4 * d, area = side * side;
  Layer l;
  l.add(side / 2, side / 2);
  const auto res = l.characterise(0, side, 0, side, d / 100);
  const double mean = 5 * pi * r * r * r / 3 / area, second = 17 * pi * std::pow(r, 4) / 6 / area;
  const double rq = std::sqrt(second - mean * mean);
  EXPECT_NEAR(res.metrics.mean_height, mean, within * mean);
  EXPECT_NEAR(res.metrics.rq, rq, within * rq);
  EXPECT_NEAR(res.metrics.coverage, pi * r * r / area, within * pi * r * r / area);
  EXPECT_NEAR(res.metrics.largest_bare_patch, area - pi * r * r, within * (area - pi * r * r));
  // The map's peak is the sphere's top, 2 r, within the sampling offset of the nearest point.
  double peak = 0;
  for (double h : res.height) peak = std::max(peak, h);
  EXPECT_NEAR(peak, 2 * r, r * (1 - std::sqrt(1 - 0.5 * std::pow(d / 100 / r, 2))) + 1e-15);
}

}  // namespace
