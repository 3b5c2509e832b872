// A tiny linear spring-dashpot law for the engine's own tests, written with the SDK pattern: the
// ops table comes from spreadmap::detail::ContactOps<Law>::table, no plugin .so needed.
//
// Normal: F_n = K overlap - c v_n, c = 2 zeta sqrt(K m_eq), zeta from the restitution e
// (unclamped: an isolated collision rebounds with exactly e). Tangential (mu > 0 only): a linear
// spring K_t = 2/7 K on the accumulated slip (history: 3 values), capped at mu |F_n|. With
// K_t = 2/7 K the tangential oscillation of a sphere (effective mass 2/7 m with rotation) has the
// same frequency as the normal one, so natural_frequency() = sqrt(K / m_eq) covers both.
#pragma once
#include <engine/simulation.hpp>
#include <spreadmap/contact.hpp>

#include <cmath>
#include <numbers>
#include <random>

namespace spreadmap::engine::testing {

struct TestSpringDashpot {
  static constexpr int history = 3;
  double k = 100;   // normal stiffness [N/m]
  double zeta = 0;  // damping ratio [-]
  double mu = 0;    // friction coefficient [-]

  static TestSpringDashpot with_restitution(double k, double e, double mu = 0) {
    const double le = std::log(e);
    return {k, e >= 1 ? 0.0 : -le / std::sqrt(std::numbers::pi * std::numbers::pi + le * le), mu};
  }
  double natural_frequency(double m_eq, double) const { return std::sqrt(k / m_eq); }
  double damping_ratio(double, double) const { return zeta; }
  bool makes_torque() const { return mu > 0; }

  template <class Real> SM_HD ContactForce<Real> operator()(const ContactState<Real> &c, Real *h) const {
    ContactForce<Real> f;
    const Real damping = Real(2 * zeta) * std::sqrt(Real(k) * c.m_eq);
    f.normal = Real(k) * c.overlap - damping * c.v_n;
    if (mu > 0) {
      Vec3<Real> s{h[0], h[1], h[2]};
      s -= c.normal * dot(s, c.normal);  // keep the spring in the current tangent plane
      s += c.v_t * c.dt;
      const Real kt = Real(2.0 / 7.0 * k);
      Vec3<Real> ft = s * (-kt);
      const Real cap = Real(mu) * std::abs(f.normal), mag = norm(ft);
      if (mag > cap && mag > 0) {
        ft *= cap / mag;
        s = ft * (Real(-1) / kt);
      }
      h[0] = s.x;
      h[1] = s.y;
      h[2] = s.z;
      f.tangent = ft;
    }
    return f;
  }
};

inline ContactLaw bind(const TestSpringDashpot &law) {
  return {&spreadmap::detail::ContactOps<TestSpringDashpot>::table, &law};
}

inline double sphere_mass(double r, double density) { return density * 4.0 / 3.0 * std::numbers::pi * r * r * r; }

inline void push_particle(ParticleSet &s, double x, double y, double z, double r, double vx = 0, double vy = 0,
                          double vz = 0) {
  s.x.push_back(x);
  s.y.push_back(y);
  s.z.push_back(z);
  s.radius.push_back(r);
  s.vx.push_back(vx);
  s.vy.push_back(vy);
  s.vz.push_back(vz);
  s.wx.push_back(0);
  s.wy.push_back(0);
  s.wz.push_back(0);
}

// A loose random packing: a jittered lattice of `n` spheres of radius r in [lo, hi) with random
// velocities up to v_max (fixed seed: the same particles every time).
inline ParticleSet random_lattice(std::size_t n, double r, const std::array<double, 3> &lo,
                                  const std::array<double, 3> &hi, double v_max, unsigned seed = 7) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  const double pitch = 2.3 * r;
  const int nx = std::max(1, int((hi[0] - lo[0]) / pitch)), ny = std::max(1, int((hi[1] - lo[1]) / pitch));
  ParticleSet s;
  for (std::size_t k = 0; k < n; ++k) {
    const int ix = int(k % nx), iy = int((k / nx) % ny), iz = int(k / (std::size_t(nx) * ny));
    push_particle(s, lo[0] + (ix + 0.5) * pitch + 0.1 * r * u(rng), lo[1] + (iy + 0.5) * pitch + 0.1 * r * u(rng),
                  lo[2] + (iz + 0.5) * pitch + 0.1 * r * u(rng), r * (1 + 0.05 * u(rng)), v_max * u(rng),
                  v_max * u(rng), v_max * u(rng));
  }
  return s;
}

}  // namespace spreadmap::engine::testing
