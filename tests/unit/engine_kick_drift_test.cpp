// The vectorised kick-drift loops (engine/kick_drift.hpp) against the velocity-Verlet formulas
// written out per particle: the same bits for every particle whatever the range a loop gets (its
// vector body and its scalar remainder), the exact largest displacement, periodic wraps, escapes
// through open faces, and the counts of non-finite and too-fast particles.
#include <engine/kick_drift.hpp>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <gtest/gtest.h>
#include <limits>
#include <random>
#include <type_traits>
#include <vector>

namespace sm = spreadmap;
using sm::engine::KickDrift;
using sm::engine::KickDriftResult;

namespace {

// n particles in the box [0, 1) x [0, 2) x [0, 3), periodic along y, with random state.
template <class Real> struct Particles {
  std::vector<Real> x, y, z, vx, vy, vz, fx, fy, fz, wx, wy, wz, tx, ty, tz, x0, y0, z0, inv_m, inv_i, mobile;
  KickDrift<Real> k{};

  explicit Particles(std::size_t n, unsigned seed = 7) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(0, 1), s(-1, 1);
    for (auto *a : {&x,  &y,  &z,  &vx, &vy, &vz, &fx, &fy,    &fz,    &wx,    &wy,
                    &wz, &tx, &ty, &tz, &x0, &y0, &z0, &inv_m, &inv_i, &mobile})
      a->resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      x[i] = Real(0.2 + 0.6 * u(rng));
      y[i] = Real(2 * u(rng));
      z[i] = Real(0.5 + 2 * u(rng));
      x0[i] = x[i] + Real(0.01 * s(rng));
      y0[i] = y[i] + Real(0.01 * s(rng));
      z0[i] = z[i] + Real(0.01 * s(rng));
      vx[i] = Real(s(rng));
      vy[i] = Real(40 * s(rng));
      vz[i] = Real(s(rng));  // some cross y = 0 or 2
      wx[i] = Real(s(rng));
      wy[i] = Real(s(rng));
      wz[i] = Real(s(rng));
      fx[i] = Real(s(rng));
      fy[i] = Real(s(rng));
      fz[i] = Real(s(rng));
      tx[i] = Real(s(rng));
      ty[i] = Real(s(rng));
      tz[i] = Real(s(rng));
      inv_m[i] = Real(1 + u(rng));
      inv_i[i] = Real(10 + u(rng));
      mobile[i] = 1;
    }
    k = {x.data(),      y.data(),     z.data(),     vx.data(),
         vy.data(),     vz.data(),    fx.data(),    fy.data(),
         fz.data(),     wx.data(),    wy.data(),    wz.data(),
         tx.data(),     ty.data(),    tz.data(),    x0.data(),
         y0.data(),     z0.data(),    inv_m.data(), inv_i.data(),
         mobile.data(), Real(0.5e-2), Real(1e-2),   {0, 0, Real(-9.81)},
         {0, 0, 0},     {1, 2, 3},    {1, 2, 3},    {false, true, false},
         true,          false};
  }
};

// The first half kick and drift of particle i written out: returns its squared displacement.
template <class Real> Real expected_kick_drift(const Particles<Real> &p, std::size_t i, Real out[6]) {
  const Real h = p.k.half_dt, dt = p.k.dt;
  const Real vx = p.vx[i] + h * (p.fx[i] * p.inv_m[i] + p.k.g[0]);
  const Real vy = p.vy[i] + h * (p.fy[i] * p.inv_m[i] + p.k.g[1]);
  const Real vz = p.vz[i] + h * (p.fz[i] * p.inv_m[i] + p.k.g[2]);
  out[0] = p.x[i] + dt * vx;
  Real y = p.y[i] + dt * vy;
  y = y >= Real(2) ? y - Real(2) : (y < Real(0) ? y + Real(2) : y);
  out[1] = y;
  out[2] = p.z[i] + dt * vz;
  out[3] = vx;
  out[4] = vy;
  out[5] = vz;
  Real dy = y - p.y0[i];
  dy = dy > Real(1) ? dy - Real(2) : (dy < Real(-1) ? dy + Real(2) : dy);
  const Real dx = out[0] - p.x0[i], dz = out[2] - p.z0[i];
  return dx * dx + dy * dy + dz * dz;
}

template <class Real> void check_kick_drift() {
  for (std::size_t n : {1u, 3u, 37u, 1000u}) {
    Particles<Real> p(n);
    std::vector<Real> expected(6 * n), d2(n);
    Real largest = 0;
    for (std::size_t i = 0; i < n; ++i) {
      d2[i] = expected_kick_drift(p, i, &expected[6 * i]);
      largest = std::max(largest, d2[i]);
    }
    // two ranges of odd lengths: vector bodies and scalar remainders both run
    KickDriftResult<Real> result;
    const long long cut = static_cast<long long>(n) / 3;
    sm::engine::kick_drift(p.k, 0, cut, result);
    sm::engine::kick_drift(p.k, cut, static_cast<long long>(n), result);
    std::size_t crossed = 0;
    for (std::size_t i = 0; i < n; ++i) {
      ASSERT_EQ(p.x[i], expected[6 * i]) << "particle " << i << " of " << n;
      ASSERT_EQ(p.y[i], expected[6 * i + 1]) << "particle " << i << " of " << n;
      ASSERT_EQ(p.z[i], expected[6 * i + 2]) << "particle " << i << " of " << n;
      ASSERT_EQ(p.vx[i], expected[6 * i + 3]);
      ASSERT_EQ(p.vy[i], expected[6 * i + 4]);
      ASSERT_EQ(p.vz[i], expected[6 * i + 5]);
      ASSERT_EQ(p.fx[i], Real(0)) << "the accumulators are used up";
      ASSERT_GE(p.y[i], Real(0));
      ASSERT_LT(p.y[i], Real(2));
      crossed += std::abs(p.y[i] - p.y0[i]) > Real(1) ? 1u : 0u;
    }
    EXPECT_EQ(result.largest, largest) << n << " particles";
    EXPECT_EQ(result.escaped, 0u);
    EXPECT_EQ(result.nonfinite, 0u);
    if (n == 1000) {
      EXPECT_GT(crossed, 10u) << "some particles should have wrapped around y";
    }
  }
}

}  // namespace

TEST(KickDrift, DoubleGivesTheFormulasBitsAndTheExactLargestDisplacement) { check_kick_drift<double>(); }
TEST(KickDrift, FloatGivesTheFormulasBitsAndTheExactLargestDisplacement) { check_kick_drift<float>(); }

TEST(KickDrift, CountsEscapesThroughOpenFacesAndNonFinitePositions) {
  Particles<double> p(41);
  p.vx[5] = 200;     // leaves through x = 1 (open)
  p.vz[17] = -1000;  // through z = 0
  p.vx[30] = std::numeric_limits<double>::quiet_NaN();
  p.vz[40] = std::numeric_limits<double>::infinity();
  KickDriftResult<double> result;
  sm::engine::kick_drift(p.k, 0, 41, result);
  EXPECT_EQ(result.escaped, 2u);
  EXPECT_EQ(result.nonfinite, 2u);
}

TEST(KickDrift, SecondKickCountsTooFastAndNonFiniteParticles) {
  Particles<double> p(29);
  p.vy[3] = 1e3;
  p.wz[11] = std::numeric_limits<double>::infinity();
  p.vx[28] = std::numeric_limits<double>::quiet_NaN();
  const double vx7 = p.vx[7] + p.k.half_dt * (p.fx[7] * p.inv_m[7] + p.k.g[0]);
  const double wy7 = p.wy[7] + p.k.half_dt * (p.ty[7] * p.inv_i[7]);
  EXPECT_EQ(sm::engine::kick_check(p.k, 100.0 * 100.0, 0, 29), 3u);
  EXPECT_EQ(p.vx[7], vx7);
  EXPECT_EQ(p.wy[7], wy7);
}

namespace {
// The fused pass (the last step's second half kick and check, this step's first half kick and
// drift) against the two passes it replaces, on a copy of the same particles: every bit of the
// state and every count the same, whatever the ranges, with and without rotation.
template <class Real> void check_fused_pass(bool rotate) {
  for (std::size_t n : {1u, 5u, 37u, 1000u}) {
    Particles<Real> fused(n, 11), apart(n, 11);
    fused.k.rotate = apart.k.rotate = rotate;
    fused.vy[n / 2] = Real(1e3);  // too fast after the second half kick
    apart.vy[n / 2] = Real(1e3);
    const Real limit2 = Real(100 * 100);
    const long long cut = static_cast<long long>(n) / 3, end = static_cast<long long>(n);
    KickDriftResult<Real> by_fused, by_apart;
    const std::uint32_t bad_fused = sm::engine::kick_check_drift(fused.k, limit2, 0, cut, by_fused) +
                                    sm::engine::kick_check_drift(fused.k, limit2, cut, end, by_fused);
    const std::uint32_t bad_apart = sm::engine::kick_check(apart.k, limit2, 0, end);
    sm::engine::kick_drift(apart.k, 0, end, by_apart);
    EXPECT_EQ(bad_fused, 1u);
    EXPECT_EQ(bad_fused, bad_apart);
    EXPECT_EQ(by_fused.largest, by_apart.largest);
    EXPECT_EQ(by_fused.escaped, by_apart.escaped);
    EXPECT_EQ(by_fused.nonfinite, by_apart.nonfinite);
    auto columns = [](Particles<Real> &p) {
      return std::vector<std::vector<Real> *>{&p.x,  &p.y,  &p.z,  &p.vx, &p.vy, &p.vz, &p.wx, &p.wy,
                                              &p.wz, &p.fx, &p.fy, &p.fz, &p.tx, &p.ty, &p.tz};
    };
    using Bits = std::conditional_t<sizeof(Real) == 8, std::uint64_t, std::uint32_t>;
    const auto a = columns(fused), b = columns(apart);
    for (std::size_t c = 0; c < a.size(); ++c)
      for (std::size_t i = 0; i < n; ++i)
        ASSERT_EQ(std::bit_cast<Bits>((*a[c])[i]), std::bit_cast<Bits>((*b[c])[i]))
            << "column " << c << ", particle " << i << " of " << n << (rotate ? ", rotating" : "");
    if (rotate) {
      EXPECT_NE(fused.wx[0], Particles<Real>(n, 11).wx[0]) << "the spins were kicked";
    }
  }
}
}  // namespace

TEST(KickDrift, FusedPassGivesTheBitsOfTheTwoPassesInDouble) {
  check_fused_pass<double>(true);
  check_fused_pass<double>(false);
}
TEST(KickDrift, FusedPassGivesTheBitsOfTheTwoPassesInFloat) {
  check_fused_pass<float>(true);
  check_fused_pass<float>(false);
}
