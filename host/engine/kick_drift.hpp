// The two half kicks of a velocity-Verlet step over a range of particles, compiled once per
// combination of periodic axes and rotation so that the loops have no branch left and vectorise.
// First: w += dt/2 T/I (when rotating); v += dt/2 (F/m + g); F = T = 0 (the accumulators are used
// up); x += dt v, wrapped along periodic axes; the largest squared displacement since the list
// build. Second (after the forces): the same kick, and a count of particles too fast or not finite.
#pragma once
#include <cstdint>

namespace spreadmap::engine {

template <class Real> struct KickDrift {
  Real *x, *y, *z, *vx, *vy, *vz, *fx, *fy, *fz, *wx, *wy, *wz, *tx, *ty, *tz;
  const Real *x0, *y0, *z0, *inv_m, *inv_i;
  Real half_dt, dt, g[3], lo[3], hi[3], len[3];
  bool periodic[3], rotate;
};

// What a range of particles reports: particles outside an open axis (with finite positions), non-finite
// positions, and the largest squared displacement.
template <class Real> struct KickDriftResult {
  std::uint32_t escaped = 0, nonfinite = 0;
  Real largest = 0;
};

namespace detail {
template <class Real, bool Periodic>
inline Real drift_axis(Real pos, Real v, Real dt, Real lo, Real hi, Real len, std::uint32_t &out) {
  const Real q = pos + dt * v;
  if constexpr (Periodic) {
    return q >= hi ? q - len : (q < lo ? q + len : q);
  } else {
    out |= (q >= lo) & (q < hi) ? 0u : 1u;
    return q;
  }
}
template <class Real, bool Periodic> inline Real moved_axis(Real pos, Real ref, Real len) {
  const Real d = pos - ref;
  if constexpr (Periodic) {
    const Real h = Real(0.5) * len;
    return d > h ? d - len : (d < -h ? d + len : d);
  } else {
    return d;
  }
}

template <class Real, bool PX, bool PY, bool PZ, bool Rotate>
void kick_drift_range(const KickDrift<Real> &k, long long begin, long long end, KickDriftResult<Real> &result) {
  std::uint32_t escaped = 0, nonfinite = 0;
  Real largest = 0;
  // Locals: stores through the arrays cannot then be taken to change them.
  Real *x = k.x, *y = k.y, *z = k.z, *vx = k.vx, *vy = k.vy, *vz = k.vz, *fx = k.fx, *fy = k.fy, *fz = k.fz;
  Real *wx = k.wx, *wy = k.wy, *wz = k.wz, *tx = k.tx, *ty = k.ty, *tz = k.tz;
  const Real *x0 = k.x0, *y0 = k.y0, *z0 = k.z0, *inv_m = k.inv_m, *inv_i = k.inv_i;
  const Real h = k.half_dt, dt = k.dt, gx = k.g[0], gy = k.g[1], gz = k.g[2];
  const Real lx = k.lo[0], ly = k.lo[1], lz = k.lo[2], hx = k.hi[0], hy = k.hi[1], hz = k.hi[2];
  const Real Lx = k.len[0], Ly = k.len[1], Lz = k.len[2];
#pragma omp simd reduction(+ : escaped, nonfinite) reduction(max : largest)
  for (long long i = begin; i < end; ++i) {
    if constexpr (Rotate) {
      wx[i] += h * tx[i] * inv_i[i];
      wy[i] += h * ty[i] * inv_i[i];
      wz[i] += h * tz[i] * inv_i[i];
    }
    const Real ux = vx[i] + h * (fx[i] * inv_m[i] + gx);
    const Real uy = vy[i] + h * (fy[i] * inv_m[i] + gy);
    const Real uz = vz[i] + h * (fz[i] * inv_m[i] + gz);
    vx[i] = ux; vy[i] = uy; vz[i] = uz;
    fx[i] = 0; fy[i] = 0; fz[i] = 0;
    tx[i] = 0; ty[i] = 0; tz[i] = 0;
    std::uint32_t out = 0;
    const Real px = drift_axis<Real, PX>(x[i], ux, dt, lx, hx, Lx, out);
    const Real py = drift_axis<Real, PY>(y[i], uy, dt, ly, hy, Ly, out);
    const Real pz = drift_axis<Real, PZ>(z[i], uz, dt, lz, hz, Lz, out);
    x[i] = px; y[i] = py; z[i] = pz;
    const Real dx = moved_axis<Real, PX>(px, x0[i], Lx), dy = moved_axis<Real, PY>(py, y0[i], Ly),
               dz = moved_axis<Real, PZ>(pz, z0[i], Lz);
    const Real d2 = dx * dx + dy * dy + dz * dz;
    const std::uint32_t finite = ((px - px) == 0) & ((py - py) == 0) & ((pz - pz) == 0);  // inf - inf is NaN
    nonfinite += 1u - finite;
    escaped += out & finite;
    largest = largest > d2 ? largest : d2;
  }
  result.escaped += escaped;
  result.nonfinite += nonfinite;
  result.largest = result.largest > largest ? result.largest : largest;
}

template <class Real, bool Rotate>
std::uint32_t kick_check_range(const KickDrift<Real> &k, Real limit2, long long begin, long long end) {
  Real *vx = k.vx, *vy = k.vy, *vz = k.vz, *wx = k.wx, *wy = k.wy, *wz = k.wz;
  const Real *fx = k.fx, *fy = k.fy, *fz = k.fz, *tx = k.tx, *ty = k.ty, *tz = k.tz, *inv_m = k.inv_m,
             *inv_i = k.inv_i;
  const Real h = k.half_dt, gx = k.g[0], gy = k.g[1], gz = k.g[2];
  std::uint32_t bad = 0;
#pragma omp simd reduction(+ : bad)
  for (long long i = begin; i < end; ++i) {
    if constexpr (Rotate) {
      wx[i] += h * tx[i] * inv_i[i];
      wy[i] += h * ty[i] * inv_i[i];
      wz[i] += h * tz[i] * inv_i[i];
    }
    const Real ux = vx[i] + h * (fx[i] * inv_m[i] + gx);
    const Real uy = vy[i] + h * (fy[i] * inv_m[i] + gy);
    const Real uz = vz[i] + h * (fz[i] * inv_m[i] + gz);
    vx[i] = ux; vy[i] = uy; vz[i] = uz;
    const Real v2 = ux * ux + uy * uy + uz * uz;
    const Real w2 = wx[i] * wx[i] + wy[i] * wy[i] + wz[i] * wz[i];
    bad += (!(v2 <= limit2) | !((w2 - w2) == 0)) ? 1u : 0u;  // NaN fails the comparison; inf - inf is NaN
  }
  return bad;
}
}  // namespace detail

// Second half kick of particles [begin, end); returns how many are faster than sqrt(limit2) or have
// a non-finite velocity or spin.
template <class Real>
std::uint32_t kick_check(const KickDrift<Real> &k, Real limit2, long long begin, long long end) {
  return k.rotate ? detail::kick_check_range<Real, true>(k, limit2, begin, end)
                  : detail::kick_check_range<Real, false>(k, limit2, begin, end);
}

// First half kick and drift of particles [begin, end); adds to `result`.
template <class Real>
void kick_drift(const KickDrift<Real> &k, long long begin, long long end, KickDriftResult<Real> &result) {
  const int code = (k.periodic[0] ? 1 : 0) | (k.periodic[1] ? 2 : 0) | (k.periodic[2] ? 4 : 0) | (k.rotate ? 8 : 0);
  using detail::kick_drift_range;
  switch (code) {
    case 0: return kick_drift_range<Real, false, false, false, false>(k, begin, end, result);
    case 1: return kick_drift_range<Real, true, false, false, false>(k, begin, end, result);
    case 2: return kick_drift_range<Real, false, true, false, false>(k, begin, end, result);
    case 3: return kick_drift_range<Real, true, true, false, false>(k, begin, end, result);
    case 4: return kick_drift_range<Real, false, false, true, false>(k, begin, end, result);
    case 5: return kick_drift_range<Real, true, false, true, false>(k, begin, end, result);
    case 6: return kick_drift_range<Real, false, true, true, false>(k, begin, end, result);
    case 7: return kick_drift_range<Real, true, true, true, false>(k, begin, end, result);
    case 8: return kick_drift_range<Real, false, false, false, true>(k, begin, end, result);
    case 9: return kick_drift_range<Real, true, false, false, true>(k, begin, end, result);
    case 10: return kick_drift_range<Real, false, true, false, true>(k, begin, end, result);
    case 11: return kick_drift_range<Real, true, true, false, true>(k, begin, end, result);
    case 12: return kick_drift_range<Real, false, false, true, true>(k, begin, end, result);
    case 13: return kick_drift_range<Real, true, false, true, true>(k, begin, end, result);
    case 14: return kick_drift_range<Real, false, true, true, true>(k, begin, end, result);
    default: return kick_drift_range<Real, true, true, true, true>(k, begin, end, result);
  }
}

}  // namespace spreadmap::engine
