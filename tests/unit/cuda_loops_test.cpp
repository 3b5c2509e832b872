// The host-device bodies of the SDK loops (pair_forces_on, wall_force_on, geometry_contact_of), run on
// the CPU with the in-tree laws and spreaders. A CUDA kernel runs them one thread per particle in an
// order nobody controls; these tests replay such a schedule on the CPU and check what the GPU relies
// on: each body writes only its own particle and its own list entries, so any schedule gives the exact
// bits of the particles in order; pair forces are equal and opposite; apart pairs forget their history.
#include <gtest/gtest.h>
#include <spreadmap/contact.hpp>
#include <spreadmap/geometry.hpp>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <vector>

#include "gpu/plugin_params.hpp"
#include "gpu/random_packing.hpp"
#include "verification/contact_laws.hpp"
#include "plugins/spreader/blade/blade.hpp"
#include "plugins/spreader/roller/roller.hpp"

namespace sm = spreadmap;
using nlohmann::json;

namespace {

constexpr unsigned block = 128;  // threads per block of the CUDA kernels

// Blocks in a shuffled order, the threads of a block in reverse order: one of the schedules a GPU
// may run, and not the loop's.
template <class Body> void gpu_schedule(std::uint32_t n, Body body) {
  std::vector<std::uint32_t> blocks((n + block - 1) / block);
  std::iota(blocks.begin(), blocks.end(), 0u);
  std::shuffle(blocks.begin(), blocks.end(), std::mt19937(7));
  for (std::uint32_t b : blocks)
    for (std::uint32_t t = block; t-- > 0;)
      if (const std::uint32_t i = b * block + t; i < n) body(i);
}

// The particles in increasing order: the loop a host before ABI 10.3 calls.
template <class Body> void in_order(std::uint32_t n, Body body) {
  for (std::uint32_t i = 0; i < n; ++i) body(i);
}

template <class Law> sm::test::PackingSpec spec_for() {
  sm::test::PackingSpec s;
  s.n = 1500;
  s.history_values = Law::history;
  return s;
}

template <class Law> void expect_schedule_independent_pairs(const Law &law) {
  auto loop = sm::test::make_packing<double>(spec_for<Law>());
  auto kernel = loop;
  const auto lp = loop.particles();
  const auto ll = loop.pairs();
  in_order(lp.n, [&](std::uint32_t i) { sm::pair_forces_on(law, lp, ll, i); });
  const auto p = kernel.particles();
  const auto l = kernel.pairs();
  gpu_schedule(p.n, [&](std::uint32_t i) { sm::pair_forces_on(law, p, l, i); });
  EXPECT_EQ(kernel.fx, loop.fx);
  EXPECT_EQ(kernel.fy, loop.fy);
  EXPECT_EQ(kernel.fz, loop.fz);
  EXPECT_EQ(kernel.tx, loop.tx);
  EXPECT_EQ(kernel.ty, loop.ty);
  EXPECT_EQ(kernel.tz, loop.tz);
  EXPECT_EQ(kernel.hist, loop.hist);
  EXPECT_GT(*std::max_element(loop.fz.begin(), loop.fz.end()), 0.0) << "the packing has contacts";
}

template <class Law> void expect_schedule_independent_walls(const Law &law) {
  const auto spec = spec_for<Law>();
  auto loop = sm::test::make_packing<double>(spec);
  auto kernel = loop;
  auto lw = sm::test::make_wall_records(loop, spec);
  auto kw = lw;
  const auto lp = loop.particles();
  const auto lwv = lw.view();
  in_order(lp.n, [&](std::uint32_t i) { sm::wall_force_on(law, lp, lwv, i); });
  const auto p = kernel.particles();
  const auto w = kw.view();
  gpu_schedule(p.n, [&](std::uint32_t i) { sm::wall_force_on(law, p, w, i); });
  EXPECT_EQ(kernel.fx, loop.fx);
  EXPECT_EQ(kernel.fz, loop.fz);
  EXPECT_EQ(kernel.ty, loop.ty);
  EXPECT_EQ(kw.hist, lw.hist);
}

// Newton's third law through the full (both-direction) list: with no prior history each contact's
// force is computed once from each side, exactly opposite, so the total is zero to round-off.
template <class Law> void expect_momentum_conserved(const Law &law) {
  auto spec = spec_for<Law>();
  spec.history = 0;
  auto k = sm::test::make_packing<double>(spec);
  const auto kp = k.particles();
  const auto kl = k.pairs();
  in_order(kp.n, [&](std::uint32_t i) { sm::pair_forces_on(law, kp, kl, i); });
  for (const auto *f : {&k.fx, &k.fy, &k.fz}) {
    const double total = std::accumulate(f->begin(), f->end(), 0.0);
    double magnitude = 0;
    for (double v : *f) magnitude += std::abs(v);
    EXPECT_GT(magnitude, 0);
    EXPECT_LE(std::abs(total), 1e-12 * magnitude);
  }
}

// Parameters a law needs beyond its schema defaults (hertz_mindlin's Young's modulus is required).
template <class Law> json required_params() { return json::object(); }
template <> json required_params<sm::HertzMindlin>() { return {{"youngs_modulus", 1e8}}; }
// The schedule check also runs hooke_slider's rolling-friction torque.
template <class Law> json schedule_params() { return required_params<Law>(); }
template <> json schedule_params<sm::HookeSlider>() { return {{"rolling_friction", 0.1}}; }

template <class Law> class CudaLoopsPerLaw : public ::testing::Test {};
TYPED_TEST_SUITE(CudaLoopsPerLaw, sm::test::ContactLaws::Types);

TYPED_TEST(CudaLoopsPerLaw, AnyKernelScheduleGivesTheLoopsBits) {
  const auto law = sm::test::bind_with<TypeParam>(schedule_params<TypeParam>());
  expect_schedule_independent_pairs(law);
  expect_schedule_independent_walls(law);
}

TYPED_TEST(CudaLoopsPerLaw, PairForcesAreEqualAndOpposite) {
  expect_momentum_conserved(sm::test::bind_with<TypeParam>(required_params<TypeParam>()));
}

// Entries whose spheres are apart (kept in the list by the skin) are reset to zero; touching ones
// carry a spring that moved on.
TEST(CudaLoops, ApartPairsForgetTheirHistoryTouchingOnesKeepIt) {
  const auto law = sm::test::bind_with<sm::HookeHistory>();
  auto k = sm::test::make_packing<double>(spec_for<sm::HookeHistory>());
  const auto before = k.hist;
  const auto p = k.particles();
  const auto l = k.pairs();
  gpu_schedule(p.n, [&](std::uint32_t i) { sm::pair_forces_on(law, p, l, i); });
  std::size_t apart = 0, touching = 0;
  const double length = k.box_hi[0] - k.box_lo[0];
  for (std::uint32_t i = 0; i < k.n; ++i)
    for (std::uint32_t e = k.start[i]; e < k.start[i + 1]; ++e) {
      const std::uint32_t j = k.nbr[e];
      const double dx = sm::wrap(k.x[i] - k.x[j], length, true), dy = sm::wrap(k.y[i] - k.y[j], length, true);
      const double dz = k.z[i] - k.z[j], reach = k.r[i] + k.r[j];
      const bool touch = dx * dx + dy * dy + dz * dz < reach * reach;
      for (unsigned q = 0; q < 3; ++q) {
        const double h = k.hist[3 * e + q];
        if (touch) EXPECT_NE(h, before[3 * e + q]);
        else EXPECT_EQ(h, 0.0);
      }
      (touch ? touching : apart) += 1;
    }
  EXPECT_GT(apart, 100u);
  EXPECT_GT(touching, 1000u);
}

// The geometry body fills a record for every particle (overlap 0 when not touching), in any schedule.
template <class Geometry> void expect_geometry_records(const Geometry &g) {
  sm::test::PackingSpec spec;
  spec.n = 1500;
  auto loop = sm::test::make_packing<double>(spec);
  loop.t = 2e-3;
  auto kernel = loop;
  auto lw = sm::test::make_wall_records(loop, spec);
  auto kw = lw;
  auto lwv = lw.view();
  const auto lp = loop.particles();
  sm::geometry_loop(g, lp, lwv, 0, lp.n);
  const auto p = kernel.particles();
  const auto w = kw.view();
  gpu_schedule(p.n, [&](std::uint32_t i) { sm::geometry_contact_of(g, p, w, i); });
  EXPECT_EQ(kw.overlap, lw.overlap);
  EXPECT_EQ(kw.nx, lw.nx);
  EXPECT_EQ(kw.nz, lw.nz);
  EXPECT_EQ(kw.vx, lw.vx);
  EXPECT_EQ(kw.vz, lw.vz);
  std::size_t touching = 0;
  for (std::uint32_t i = 0; i < loop.n; ++i) {
    EXPECT_GE(lw.overlap[i], 0.0);
    touching += lw.overlap[i] > 0;
  }
  EXPECT_GT(touching, 50u);
}

json spreader_over_packing(json params) {
  sm::test::PackingSpec spec;
  spec.n = 1500;
  const auto k = sm::test::make_packing<double>(spec);
  params["gap"] = *std::max_element(k.z.begin(), k.z.end()) - 0.3e-3;
  params["U"] = 0.05;
  params["start"] = 0.5 * (k.box_hi[0] - k.box_lo[0]) - 0.05 * 2e-3;
  return params;
}

TEST(CudaLoops, RollerRecordsAreScheduleIndependent) {
  expect_geometry_records(
      sm::test::bind_with<sm::spreader::Roller>(spreader_over_packing({{"diameter", 2e-3}, {"omega", -20.0}})));
}

TEST(CudaLoops, BladeRecordsAreScheduleIndependent) {
  expect_geometry_records(
      sm::test::bind_with<sm::spreader::Blade>(spreader_over_packing({{"thickness", 1e-3}, {"edge_radius", 0.2e-3}})));
}

}  // namespace
