// The rough substrate (host/powder/rough_substrate): the statistics of its Gaussian random height
// field against the request (R_q exactly, by construction; the correlation length within the
// sampling error of one field), the sphere layer built on it, and a sphere dropped onto that layer
// resting on it instead of falling through (engine, the layer's spheres fixed).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "engine_test_law.hpp"
#include "powder/rough_substrate.hpp"

namespace sm = spreadmap;
using sm::powder::HeightField;

namespace {

constexpr double um = 1e-6;

// Normalised autocorrelation of the field at lag k lattice points along x (pairs inside the field)
// or along y (wrapped when periodic).
double autocorrelation(const HeightField &f, std::size_t k, bool along_x, bool periodic_y = false) {
  double sum = 0, sq = 0;
  std::size_t pairs = 0;
  for (double v : f.h) sq += v * v;
  for (std::size_t iy = 0; iy < f.ny; ++iy)
    for (std::size_t ix = 0; ix < f.nx; ++ix) {
      std::size_t jx = ix, jy = iy;
      if (along_x) jx += k;
      else jy = periodic_y ? (iy + k) % f.ny : iy + k;
      if (jx >= f.nx || jy >= f.ny) continue;
      sum += f.h[iy * f.nx + ix] * f.h[jy * f.nx + jx];
      ++pairs;
    }
  return (sum / static_cast<double>(pairs)) / (sq / static_cast<double>(f.h.size()));
}

// The lag [m] where the autocorrelation first falls below 1/e, interpolated linearly between lattice lags.
double correlation_length(const HeightField &f, bool along_x, bool periodic_y = false) {
  const double spacing = along_x ? f.dx : f.dy;
  double before = 1;
  for (std::size_t k = 1; k < (along_x ? f.nx : f.ny); ++k) {
    const double c = autocorrelation(f, k, along_x, periodic_y);
    if (c < std::exp(-1.0)) return spacing * (static_cast<double>(k) - (std::exp(-1.0) - c) / (before - c));
    before = c;
  }
  return NAN;
}

double rms(const std::vector<double> &v) {
  double mean = 0, sq = 0;
  for (double x : v) mean += x;
  mean /= static_cast<double>(v.size());
  for (double x : v) sq += (x - mean) * (x - mean);
  return std::sqrt(sq / static_cast<double>(v.size()));
}

}  // namespace

// 400 x 400 points, xi = 8 spacings: about 2500 independent patches, so one field's autocorrelation
// is within a few percent of exp(-r^2 / xi^2). Measured over seeds 1-6, periodic or not: xi -3.5 % to
// +2.5 %, the autocorrelation at lags 2-12 within 0.021; the tolerances (8 %, 0.05) are over twice that.
TEST(SceneRoughSubstrate, FieldHasTheRequestedRqAndCorrelationLength) {
  const double rq = 10 * um, xi = 80 * um, dx = 10 * um;
  for (const bool periodic : {false, true}) {
    const HeightField f = sm::powder::gaussian_height_field(400, 400, dx, dx, rq, xi, periodic, 3);
    EXPECT_NEAR(rms(f.h), rq, 1e-12 * rq);
    for (const std::size_t k : {2u, 4u, 8u, 12u})
      EXPECT_NEAR(autocorrelation(f, k, true), std::exp(-std::pow(k * dx / xi, 2)), 0.05) << "lag " << k;
    EXPECT_NEAR(correlation_length(f, true), xi, 0.08 * xi);
    EXPECT_NEAR(correlation_length(f, false, periodic), xi, 0.08 * xi) << "periodic " << periodic;
  }
}

// The coarsest lattice allowed (spacing xi / 2) still carries the correlation length (measured over
// seeds 11-13: the autocorrelation within 0.005, xi within 1 %).
TEST(SceneRoughSubstrate, CoarsestLatticeKeepsTheCorrelationLength) {
  const double xi = 100 * um, dx = 50 * um;
  const HeightField f = sm::powder::gaussian_height_field(800, 800, dx, dx, 5 * um, xi, true, 11);
  EXPECT_NEAR(autocorrelation(f, 1, true), std::exp(-0.25), 0.03);
  EXPECT_NEAR(autocorrelation(f, 2, true), std::exp(-1.0), 0.03);
  EXPECT_NEAR(correlation_length(f, true), xi, 0.08 * xi);
}

TEST(SceneRoughSubstrate, RefusesWhatTheLatticeCannotCarry) {
  EXPECT_THROW(sm::powder::gaussian_height_field(10, 10, 50 * um, 50 * um, 5 * um, 90 * um, false, 1),
               std::invalid_argument);  // xi below 2 spacings
  EXPECT_THROW(sm::powder::gaussian_height_field(10, 10, 50 * um, 50 * um, -1 * um, 200 * um, false, 1),
               std::invalid_argument);
  EXPECT_THROW(sm::powder::gaussian_height_field(0, 10, 50 * um, 50 * um, 5 * um, 200 * um, false, 1),
               std::invalid_argument);
}

// The spheres: one per lattice point, the lowest touching z = 0, tops following the field (their
// R_q is the request), never overlapping one another, the lattice wrapping across a periodic y.
TEST(SceneRoughSubstrate, SphereLayerFollowsTheField) {
  sm::powder::RoughnessSpec spec{10 * um, 200 * um, 50 * um, 4e-3, 1.03e-3, true, 5};
  const auto s = sm::powder::rough_substrate(spec);
  ASSERT_EQ(s.x.size(), 80u * 20u);
  EXPECT_DOUBLE_EQ(s.field.dy, 1.03e-3 / 20);
  std::vector<double> tops, bottoms;
  for (std::size_t i = 0; i < s.z.size(); ++i) tops.push_back(s.z[i] + s.radius), bottoms.push_back(s.z[i] - s.radius);
  EXPECT_NEAR(rms(tops), 10 * um, 1e-9 * um);
  EXPECT_NEAR(*std::min_element(bottoms.begin(), bottoms.end()), 0.0, 1e-18);
  double mean = 0;
  for (double t : tops) mean += t;
  EXPECT_NEAR(s.mean_top, mean / static_cast<double>(tops.size()), 1e-15);
  for (std::size_t i = 0; i + 1 < s.x.size(); ++i) {  // neighbours along x: at least one diameter apart
    if (s.y[i] != s.y[i + 1]) continue;
    EXPECT_GE(std::hypot(s.x[i + 1] - s.x[i], s.z[i + 1] - s.z[i]), 2 * s.radius * (1 - 1e-12));
  }
}

// A sphere of the lattice's diameter dropped onto the rough layer (fixed spheres, spacing = d) comes
// to rest on it: its centre ends above the tops of the four spheres under it (a sphere in the hollow of
// four touching ones sits d / sqrt(2) above their centres), it never reaches the plate, and the layer
// does not move.
TEST(SceneRoughSubstrate, ASphereRestsOnTheLayerAndDoesNotFallThrough) {
  using namespace sm::engine;
  using namespace sm::engine::testing;
  const double d = 100 * um;
  sm::powder::RoughnessSpec spec{10 * um, 300 * um, d, 1e-3, 1e-3, true, 9};
  const auto layer = sm::powder::rough_substrate(spec);
  TestSpringDashpot law = TestSpringDashpot::with_restitution(5, 0.3);
  Settings settings;
  settings.log = [](const std::string &) {};
  Simulation<double> sim({{0, 0, 0}, {1e-3, 1e-3, 1e-3}, {true, true, false}}, bind(law), settings);
  sim.add_plane_wall({{0, 0, 0}, {0, 0, 1}, {0, 0, 0}, bind(law), true, "plate"});
  ParticleSet set;
  for (std::size_t i = 0; i < layer.x.size(); ++i) {
    push_particle(set, layer.x[i], layer.y[i], layer.z[i], layer.radius);
    set.fixed.push_back(1);
  }
  const double x = 0.5e-3, y = 0.5e-3;  // a hollow between four lattice points
  push_particle(set, x, y, 0.5e-3, d / 2);
  set.fixed.push_back(0);
  sim.add_particles(set, 4430);
  ASSERT_EQ(sim.fixed_count(), layer.x.size());
  while (sim.time() < 0.04) sim.step();  // falls in 8 ms, then settles
  const ParticleSet state = sim.state();
  ASSERT_EQ(state.fixed.size(), state.size());
  double highest_below = 0, free_z = 0, free_speed = 0;
  for (std::size_t i = 0; i < state.size(); ++i) {
    if (!state.fixed[i]) {
      free_z = state.z[i];
      free_speed = std::sqrt(state.vx[i] * state.vx[i] + state.vy[i] * state.vy[i] + state.vz[i] * state.vz[i]);
    } else if (std::abs(state.x[i] - x) < d && std::abs(state.y[i] - y) < d) {
      highest_below = std::max(highest_below, state.z[i]);
    }
  }
  EXPECT_GT(free_z, highest_below + d / 2)
      << "centre " << free_z / um << " um, layer centres up to " << highest_below / um << " um";
  EXPECT_GT(free_z - d / 2, 0.0);
  EXPECT_LT(free_speed, 1e-3);  // at rest
  for (std::size_t i = 0; i < state.size(); ++i)
    if (state.fixed[i]) {
      EXPECT_EQ(state.vz[i], 0.0);
    }
}

// A measured surface (sampled_height_field): bilinear is exact for a plane inside one tile of the map;
// on lattice points that fall on map points the field is the map there; a domain larger than the map
// repeats it with the map's period.
TEST(MeasuredSubstrate, ALatticeSamplesAPlaneExactlyAndRepeatsTheMapBeyondItsTile) {
  const double step = 10 * um;
  HeightField map{12, 8, step, step, {}};
  for (std::size_t j = 0; j < map.ny; ++j)
    for (std::size_t i = 0; i < map.nx; ++i) map.h.push_back(3e-3 * double(i) * step - 2e-3 * double(j) * step);
  // lattice points at (k + 1/2) 25 um: inside the tile's first 11 x 7 cells, away from its wrap-around cell
  const HeightField plane = sm::powder::sampled_height_field(map, 4, 2, 25 * um, 25 * um);
  for (std::size_t iy = 0; iy < 2; ++iy)
    for (std::size_t ix = 0; ix < 4; ++ix) {
      const double x = (double(ix) + 0.5) * 25 * um, y = (double(iy) + 0.5) * 25 * um;
      EXPECT_NEAR(plane.h[iy * 4 + ix], 3e-3 * x - 2e-3 * y, 1e-18) << ix << ", " << iy;
    }

  // spheres of 20 um on a map of 10 um spacing: every centre on a map point; 3 tiles along x
  HeightField wave{6, 4, step, step, {}};
  for (std::size_t j = 0; j < wave.ny; ++j)
    for (std::size_t i = 0; i < wave.nx; ++i)
      wave.h.push_back(5 * um * std::sin(2 * M_PI * double(i) / 6) + 1 * um * double(j));
  const HeightField tiled = sm::powder::sampled_height_field(wave, 9, 2, 20 * um, 20 * um);
  for (std::size_t iy = 0; iy < 2; ++iy)
    for (std::size_t ix = 0; ix < 9; ++ix) {
      const std::size_t i = (2 * ix + 1) % 6, j = 2 * iy + 1;  // the map point under the centre
      EXPECT_NEAR(tiled.h[iy * 9 + ix], wave.h[j * 6 + i], 1e-18) << ix << ", " << iy;
    }
  for (std::size_t ix = 0; ix + 3 < 9; ++ix) EXPECT_NEAR(tiled.h[ix], tiled.h[ix + 3], 1e-18) << "period 60 um";

  // the spheres stand on their tops as on a random field: lowest on the plate, mean plane the tops' mean
  sm::powder::RoughnessSpec spec;
  spec.sphere_diameter = 20 * um, spec.length = 180 * um, spec.width = 40 * um;
  const auto substrate = sm::powder::measured_substrate(wave, spec);
  ASSERT_EQ(substrate.z.size(), 18u);
  double lowest = 1, mean = 0;
  for (std::size_t k = 0; k < 18; ++k) {
    lowest = std::min(lowest, substrate.z[k] - substrate.radius);
    mean += (substrate.z[k] + substrate.radius) / 18;
    EXPECT_NEAR(substrate.z[k] + substrate.radius - (substrate.z[0] + substrate.radius), tiled.h[k] - tiled.h[0],
                1e-18);
  }
  EXPECT_NEAR(lowest, 0.0, 1e-18);
  EXPECT_NEAR(substrate.mean_top, mean, 1e-18);
  EXPECT_THROW(sm::powder::sampled_height_field(HeightField{1, 4, step, step, std::vector<double>(4)}, 2, 2, step, step),
               std::invalid_argument);
}
