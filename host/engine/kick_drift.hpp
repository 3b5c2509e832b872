// The two half kicks of a velocity-Verlet step over a range of particles, compiled once per
// combination of periodic axes, rotation and sleeping so that the loops have no branch left and
// vectorise. The per-particle pieces (half_kick, drift, too_fast) are host-device functions: the GPU
// backend's integration kernels run exactly them.
// First: w += dt/2 T/I (when rotating); v += dt/2 (F/m + g); F = T = 0 (the accumulators are used
// up); x += dt v, wrapped along periodic axes; the largest squared displacement since the list
// build. Second (after the forces): the same kick, and a count of particles too fast or not finite.
// The engine runs a step's second kick in the next step's pass (kick_check_drift): both kicks, the
// check and the drift, particle by particle.
#pragma once
#include <spreadmap/hd.hpp>
#include <spreadmap/simd.hpp>

#include <bit>
#include <cassert>
#include <cstdint>
#include <type_traits>

namespace spreadmap::engine {

template <class Real> struct KickDrift {
  Real *x, *y, *z, *vx, *vy, *vz, *fx, *fy, *fz, *wx, *wy, *wz, *tx, *ty, *tz;
  const Real *x0, *y0, *z0, *inv_m, *inv_i;
  const Real *mobile;  // 1 integrated, 0 asleep: an asleep particle keeps v = w = 0 and its place
  Real half_dt, dt, g[3], lo[3], hi[3], len[3];
  bool periodic[3], rotate;
  bool sleeping;  // some particle may be asleep: mobile is read (else every particle is integrated)
};

// What a range of particles reports: particles outside an open axis (with finite positions), non-finite
// positions, and the largest squared displacement.
template <class Real> struct KickDriftResult {
  std::uint32_t escaped = 0, nonfinite = 0;
  Real largest = 0;
};

namespace detail {
// Integers as wide as Real: a vectorised loop keeps them in the lanes of the positions. LaneCount
// counts per particle (no packing of each step's masks into 32-bit lanes); LaneBits holds a float's bits.
template <class Real> using LaneBits = std::conditional_t<sizeof(Real) == 8, std::int64_t, std::int32_t>;
template <class Real> using LaneCount = std::make_unsigned_t<LaneBits<Real>>;

template <class Real, bool Periodic>
SM_HD Real drift_axis(Real pos, Real v, Real dt, Real lo, Real hi, Real len, LaneCount<Real> &out) {
  const Real q = pos + dt * v;
  if constexpr (Periodic) {
    return q >= hi ? q - len : (q < lo ? q + len : q);
  } else {
    out |= (q >= lo) & (q < hi) ? 0 : 1;
    return q;
  }
}
template <class Real, bool Periodic> SM_HD Real moved_axis(Real pos, Real ref, Real len) {
  const Real d = pos - ref;
  if constexpr (Periodic) {
    const Real h = Real(0.5) * len;
    return d > h ? d - len : (d < -h ? d + len : d);
  } else {
    return d;
  }
}

// One half kick of particle i: w += dt/2 T/I (when rotating), v += dt/2 (F/m + g); when some may be
// asleep, both times its mobility (1, or 0 asleep: x * 1 is x exactly, so an awake particle gets the
// plain scheme's numbers).
template <class Real, bool Rotate, bool Sleep> SM_HD void half_kick(const KickDrift<Real> &k, long long i) {
  const Real h = k.half_dt;
  auto kick = [&](Real v, Real a) {
    if constexpr (Sleep) return (v + h * a) * k.mobile[i];
    else return v + h * a;
  };
  if constexpr (Rotate) {
    k.wx[i] = kick(k.wx[i], k.tx[i] * k.inv_i[i]);
    k.wy[i] = kick(k.wy[i], k.ty[i] * k.inv_i[i]);
    k.wz[i] = kick(k.wz[i], k.tz[i] * k.inv_i[i]);
  }
  k.vx[i] = kick(k.vx[i], k.fx[i] * k.inv_m[i] + k.g[0]);
  k.vy[i] = kick(k.vy[i], k.fy[i] * k.inv_m[i] + k.g[1]);
  k.vz[i] = kick(k.vz[i], k.fz[i] * k.inv_m[i] + k.g[2]);
}

// What the drift of one particle reports.
template <class Real> struct Drifted {
  Real d2;                  // squared displacement since the list build
  LaneCount<Real> escaped;  // 1: outside an open axis (with a finite position)
  LaneCount<Real> nonfinite;
};

// Drift of particle i after its first half kick: the accumulators cleared (used up), x += dt v,
// wrapped along periodic axes.
template <class Real, bool PX, bool PY, bool PZ> SM_HD Drifted<Real> drift(const KickDrift<Real> &k, long long i) {
  k.fx[i] = 0;
  k.fy[i] = 0;
  k.fz[i] = 0;
  k.tx[i] = 0;
  k.ty[i] = 0;
  k.tz[i] = 0;
  LaneCount<Real> out = 0;
  const Real px = drift_axis<Real, PX>(k.x[i], k.vx[i], k.dt, k.lo[0], k.hi[0], k.len[0], out);
  const Real py = drift_axis<Real, PY>(k.y[i], k.vy[i], k.dt, k.lo[1], k.hi[1], k.len[1], out);
  const Real pz = drift_axis<Real, PZ>(k.z[i], k.vz[i], k.dt, k.lo[2], k.hi[2], k.len[2], out);
  k.x[i] = px;
  k.y[i] = py;
  k.z[i] = pz;
  const Real dx = moved_axis<Real, PX>(px, k.x0[i], k.len[0]), dy = moved_axis<Real, PY>(py, k.y0[i], k.len[1]),
             dz = moved_axis<Real, PZ>(pz, k.z0[i], k.len[2]);
  const LaneCount<Real> finite = ((px - px) == 0) & ((py - py) == 0) & ((pz - pz) == 0);  // inf - inf is NaN
  return {dx * dx + dy * dy + dz * dz, out & finite, 1 - finite};
}

// Is particle i (after its second half kick) faster than sqrt(limit2), or is its velocity or spin
// not finite?
template <class Real>
SM_HD LaneCount<Real> too_fast(Real vx, Real vy, Real vz, Real wx, Real wy, Real wz, Real limit2) {
  const Real v2 = vx * vx + vy * vy + vz * vz;
  const Real w2 = wx * wx + wy * wy + wz * wz;
  return (!(v2 <= limit2) | !((w2 - w2) == 0)) ? 1 : 0;  // NaN fails the comparison; inf - inf is NaN
}
template <class Real> SM_HD LaneCount<Real> too_fast(const KickDrift<Real> &k, Real limit2, long long i) {
  return too_fast(k.vx[i], k.vy[i], k.vz[i], k.wx[i], k.wy[i], k.wz[i], limit2);
}

// What a loop's drifts report, summed over its particles. The largest d2 >= 0 is kept as the largest
// bit pattern (the same order for non-negative floats): an integer maximum vectorises, a floating
// one that must keep NaN's semantics does not.
template <class Real> struct DriftTally {
  using Bits = LaneBits<Real>;
  LaneCount<Real> escaped = 0, nonfinite = 0;
  Bits largest_bits = 0;
  void add(const Drifted<Real> &d) {
    nonfinite += d.nonfinite;
    escaped += d.escaped;
    const Bits b = std::bit_cast<Bits>(d.d2);
    largest_bits = largest_bits > b ? largest_bits : b;
  }
  void add_to(KickDriftResult<Real> &result) const {
    const Real largest = std::bit_cast<Real>(largest_bits);
    result.escaped += static_cast<std::uint32_t>(escaped);
    result.nonfinite += static_cast<std::uint32_t>(nonfinite);
    result.largest = result.largest > largest ? result.largest : largest;
  }
};

template <class Real, bool PX, bool PY, bool PZ, bool Rotate, bool Sleep>
void kick_drift_range(const KickDrift<Real> &k, long long begin, long long end, KickDriftResult<Real> &result) {
  DriftTally<Real> tally;
#pragma GCC ivdep
  for (long long i = begin; i < end; ++i) {
    half_kick<Real, Rotate, Sleep>(k, i);
    tally.add(drift<Real, PX, PY, PZ>(k, i));
  }
  tally.add_to(result);
}

template <class Real, bool Rotate, bool Sleep>
std::uint32_t kick_check_range(const KickDrift<Real> &k, Real limit2, long long begin, long long end) {
  LaneCount<Real> bad = 0;
#pragma GCC ivdep
  for (long long i = begin; i < end; ++i) {
    half_kick<Real, Rotate, Sleep>(k, i);
    bad += too_fast(k, limit2, i);
  }
  return static_cast<std::uint32_t>(bad);
}

// The second half kick of one step and the first of the next in one pass: each particle is kicked,
// checked and kicked again in registers, as half_kick and too_fast do it (the same operations: the
// same bits), then drifted; its velocities and forces are read from memory once instead of twice.
// No particle sleeps (a sleeping scene reads the velocities between the kicks).
template <class Real, bool PX, bool PY, bool PZ, bool Rotate>
std::uint32_t kick_check_drift_range(const KickDrift<Real> &k, Real limit2, long long begin, long long end,
                                     KickDriftResult<Real> &result) {
  DriftTally<Real> tally;
  LaneCount<Real> bad = 0;
  const Real h = k.half_dt;
#pragma GCC ivdep
  for (long long i = begin; i < end; ++i) {
    const Real ax = k.fx[i] * k.inv_m[i] + k.g[0], ay = k.fy[i] * k.inv_m[i] + k.g[1],
               az = k.fz[i] * k.inv_m[i] + k.g[2];
    Real vx = k.vx[i] + h * ax, vy = k.vy[i] + h * ay, vz = k.vz[i] + h * az;
    Real wx = k.wx[i], wy = k.wy[i], wz = k.wz[i];
    Real bx = 0, by = 0, bz = 0;  // angular acceleration
    if constexpr (Rotate) {
      bx = k.tx[i] * k.inv_i[i];
      by = k.ty[i] * k.inv_i[i];
      bz = k.tz[i] * k.inv_i[i];
      wx = wx + h * bx;
      wy = wy + h * by;
      wz = wz + h * bz;
    }
    bad += too_fast(vx, vy, vz, wx, wy, wz, limit2);
    k.vx[i] = vx + h * ax;
    k.vy[i] = vy + h * ay;
    k.vz[i] = vz + h * az;
    if constexpr (Rotate) {
      k.wx[i] = wx + h * bx;
      k.wy[i] = wy + h * by;
      k.wz[i] = wz + h * bz;
    }
    tally.add(drift<Real, PX, PY, PZ>(k, i));
  }
  tally.add_to(result);
  return static_cast<std::uint32_t>(bad);
}
}  // namespace detail

// Calls f.template operator()<b...>() with the runtime flags turned into template arguments, so that
// each combination gets a loop of its own without a branch left in it.
template <bool... Fixed, class F> void with_flags(F &&f) { f.template operator()<Fixed...>(); }
template <bool... Fixed, class F, class... Rest> void with_flags(F &&f, bool first, Rest... rest) {
  if (first) with_flags<Fixed..., true>(f, rest...);
  else with_flags<Fixed..., false>(f, rest...);
}

// Second half kick of particles [begin, end); returns how many are faster than sqrt(limit2) or have
// a non-finite velocity or spin.
template <class Real> std::uint32_t kick_check(const KickDrift<Real> &k, Real limit2, long long begin, long long end) {
  std::uint32_t bad = 0;
  with_flags(
      [&]<bool Rotate, bool Sleep>() {
        with_simd([&] { bad = detail::kick_check_range<Real, Rotate, Sleep>(k, limit2, begin, end); });
      },
      k.rotate, k.sleeping);
  return bad;
}

// First half kick and drift of particles [begin, end); adds to `result`.
template <class Real>
void kick_drift(const KickDrift<Real> &k, long long begin, long long end, KickDriftResult<Real> &result) {
  with_flags(
      [&]<bool PX, bool PY, bool PZ, bool Rotate, bool Sleep>() {
        with_simd([&] { detail::kick_drift_range<Real, PX, PY, PZ, Rotate, Sleep>(k, begin, end, result); });
      },
      k.periodic[0], k.periodic[1], k.periodic[2], k.rotate, k.sleeping);
}

// The last step's second half kick and check, then this step's first half kick and drift, of
// particles [begin, end) in one pass; adds to `result` and returns the count kick_check would. For
// scenes where no particle sleeps (k.sleeping false).
template <class Real>
std::uint32_t kick_check_drift(const KickDrift<Real> &k, Real limit2, long long begin, long long end,
                               KickDriftResult<Real> &result) {
  assert(!k.sleeping && "a sleeping scene kicks in two passes");
  std::uint32_t bad = 0;
  with_flags(
      [&]<bool PX, bool PY, bool PZ, bool Rotate>() {
        with_simd(
            [&] { bad = detail::kick_check_drift_range<Real, PX, PY, PZ, Rotate>(k, limit2, begin, end, result); });
      },
      k.periodic[0], k.periodic[1], k.periodic[2], k.rotate);
  return bad;
}

}  // namespace spreadmap::engine
