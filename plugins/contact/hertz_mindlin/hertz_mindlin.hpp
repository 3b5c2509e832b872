// contact/hertz_mindlin: Hertz normal force and Mindlin (no-slip) tangential spring with Coulomb cap,
// damping of the Tsuji (1992) / Di Renzo-Di Maio (2004) form, as in LIGGGHTS hertz + tangential history.
//
//   F_n = (4/3) E* sqrt(R delta) delta - alpha sqrt(m_eq S_n) v_n,   S_n = 2 E* sqrt(R delta)
//   F_t = -k_t s - alpha sqrt(m_t k_t) v_t, |F_t| <= mu |F_n|,       k_t = 8 G* sqrt(R delta), m_t = (2/7) m_eq
//   E* = E / (2 (1 - nu^2)),  G* = E / (4 (1 + nu) (2 - nu))  (both bodies, walls included, of one material)
//
// Damping: with sqrt(S_n) ~ delta^(1/4) the restitution does not depend on the impact speed. Unclamped,
// Di Renzo-Di Maio's alpha = -2 sqrt(5/6) ln eps / sqrt(ln^2 eps + pi^2) gives restitution eps (checked
// against the dimensionless impact x'' = -(x^(3/2) + sqrt(3/2) alpha x^(1/4) x'), x in units of
// (m v^2/k_h)^(2/5), to 1e-6 in the unit tests); eps = 0 gives alpha = 2 sqrt(5/6), where the sphere
// no longer separates. With clamp_normal (F_n >= 0) that alpha would rebound faster, so bind() solves
// the clamped dimensionless impact for the alpha that returns eps (eps must stay above the restitution
// reached at alpha = 100).
// The tangential dashpot uses m_t so that both modes share the damping ratio alpha/2.
// natural_frequency is evaluated at the Hertz stiffness of an undamped impact at v_max, whose overlap
// is delta_max = (15 m_eq v_max^2 / (16 E* sqrt(R)))^(2/5); it is the larger of the normal mode
// sqrt(S_n/m_eq) and the tangential one sqrt(k_t/m_t), so the host can pick a stable step.
// Rolling resistance optional: a constant torque or the rolling spring (epsd; docs/rolling.md).
// Optional cohesion (SJKR, DMT or JKR pull-off in contact,
// van der Waals across a gap; contact_parts.hpp, docs/cohesion.md), subtracted from F_n; across a gap
// the attraction alone acts. natural_frequency then takes the overlap of
// the impact at v_max with the attraction's work added (the SJKR softening, which only slows the
// contact, is left out: the step stays on the safe side). Units SI.
// History: 3 values per contact, the tangential spring elongation s [m] in the global frame.
#pragma once
#include <spreadmap/contact.hpp>
#include <spreadmap/contact_parts.hpp>

#include <cmath>

namespace spreadmap {

struct HertzMindlin {
  static constexpr sm_param_v1 params[] = {
      required_number("youngs_modulus", "Pa", 1e3, 1e13, "E: Young's modulus of the particles (and walls)"),
      number("poisson_ratio", "-", 0, 0.5, 0.3, "nu: Poisson's ratio of the particles (and walls)"),
      param_restitution,
      param_friction,
      param_rolling_friction,
      param_rolling_model,
      param_rolling_damping,
      param_clamp_normal,
      number("v_max", "m/s", 1e-4, 1e3, 0.5,
             "V_max: impact speed at which natural_frequency evaluates the Hertz stiffness (time step)"),
      param_cohesion_energy_density,
      param_surface_energy,
      param_pull_off,
      param_hamaker_constant,
      param_vdw_min_gap,
      param_vdw_cutoff,
  };
  static constexpr int history = 3;
  static constexpr bool history_mirrors = true;  // the spring's elongation, a global vector: -s seen from j

  double e_star;  // E* [Pa]
  double g_star;  // G* [Pa]
  double alpha;   // damping factor, calibrated to the restitution
  double mu;
  Rolling rolling;
  double v_max;  // [m/s]
  bool clamp;
  Cohesion cohesion;

  // Restitution of the dimensionless Hertz impact with damping factor alpha (RK4 with `h` time units
  // against a contact time of about 3.2; h = 2e-3 is within 2e-5 of the converged value). Not
  // separated after 60 units counts as no rebound.
  static double restitution_at(double alpha, bool clamp, double h = 2e-3) {
    const double a = alpha * std::sqrt(1.5);
    auto force = [&](double x, double v) {
      const double xp = x > 0 ? x : 0.0;
      const double f = xp * std::sqrt(xp) + a * std::sqrt(std::sqrt(xp)) * v;
      return clamp ? (f > 0 ? f : 0.0) : f;
    };
    double x = 0, v = 1;
    for (int k = 0; k * h < 60; ++k) {
      const double k1x = v, k1v = -force(x, v);
      const double k2x = v + 0.5 * h * k1v, k2v = -force(x + 0.5 * h * k1x, k2x);
      const double k3x = v + 0.5 * h * k2v, k3v = -force(x + 0.5 * h * k2x, k3x);
      const double k4x = v + h * k3v, k4v = -force(x + h * k3x, k4x);
      const double xn = x + h / 6 * (k1x + 2 * k2x + 2 * k3x + k4x);
      const double vn = v + h / 6 * (k1v + 2 * k2v + 2 * k3v + k4v);
      if (xn <= 0 && vn < 0) return -(v + (vn - v) * (x / (x - xn)));  // left the surface
      if (clamp && vn < 0 && force(xn, vn) <= 0) return -vn;           // force gone: free flight
      x = xn;
      v = vn;
    }
    return 0;
  }
  static double alpha_for_restitution(double eps, bool clamp) {
    if (eps >= 1) return 0;
    if (!clamp) return 2 * std::sqrt(5.0 / 6.0) * damping_ratio_from_restitution(eps);  // Di Renzo-Di Maio
    constexpr double alpha_max = 100;
    if (restitution_at(alpha_max, clamp) > eps)
      throw ParamError("restitution " + number_text(eps) +
                       " is below what hertz_mindlin reaches with clamp_normal "
                       "(use a larger restitution or clamp_normal: false)");
    double lo = 0, hi = alpha_max;
    for (int k = 0; k < 48; ++k) {
      const double mid = 0.5 * (lo + hi);
      (restitution_at(mid, clamp) > eps ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
  }

  static HertzMindlin bind(const Values &v) {
    const double e = v["youngs_modulus"], nu = v["poisson_ratio"];
    const bool clamp = v.boolean("clamp_normal");
    return {e / (2 * (1 - nu * nu)),
            e / (4 * (1 + nu) * (2 - nu)),
            alpha_for_restitution(v["restitution"], clamp),
            v["friction"],
            Rolling::bind(v),
            v["v_max"],
            clamp,
            Cohesion::bind(v)};
  }

  // Overlap of an undamped impact at v_max [m]: (8/15) E* sqrt(R) delta^(5/2) = m v^2/2, plus the work of
  // the attraction with cohesion (solved by bisection; the elastic energy outgrows the attraction's
  // work, so the root is the one crossing).
  double overlap_at_v_max(double m_eq, double r_eff) const {
    const double cohesionless = std::pow(15 * m_eq * v_max * v_max / (16 * e_star * std::sqrt(r_eff)), 0.4);
    if (!cohesion.on) return cohesionless;
    auto excess = [&](double d) {
      return 8.0 / 15.0 * e_star * std::sqrt(r_eff) * d * d * std::sqrt(d) - 0.5 * m_eq * v_max * v_max -
             cohesion.work(r_eff, d);
    };
    double lo = 0, hi = cohesionless;
    while (excess(hi) < 0) hi *= 2;
    for (int k = 0; k < 200 && hi - lo > 1e-14 * hi; ++k) {
      const double mid = 0.5 * (lo + hi);
      (excess(mid) < 0 ? lo : hi) = mid;
    }
    return hi;
  }
  double natural_frequency(double m_eq, double r_eff) const {
    const double a = std::sqrt(r_eff * overlap_at_v_max(m_eq, r_eff));
    const double rolling_mode = rolling.natural_frequency(4.0 / 3.0 * e_star * a, m_eq);  // secant k_n
    return max(std::sqrt(max(2 * e_star * a / m_eq, 8 * g_star * a / tangential_mass(m_eq))), rolling_mode);
  }
  double damping_ratio(double, double) const { return alpha / 2; }
  bool makes_torque() const { return mu > 0 || rolling.mu_r > 0; }

  // Without the rolling spring (Law::history values in hist); the loops reach it through in_loop_form.
  template <class Real> SM_HD ContactForce<Real> operator()(const ContactState<Real> &c, Real *hist) const {
    return cohesion.on ? force<true, RollingForm::constant>(c, hist) : force<false, RollingForm::constant>(c, hist);
  }
  // hist: the tangential spring's 3 values, then the rolling spring's 3 (Spring).
  template <bool Cohesive, RollingForm Rolls, class Real>
  SM_HD ContactForce<Real> force(const ContactState<Real> &c, Real *hist) const {
    ContactForce<Real> f;
    const Real a = std::sqrt(c.r_eff * c.overlap);  // contact radius
    const Real s_n = Real(2 * e_star) * a, k_t = Real(8 * g_star) * a;
    const Real fn = Real(2) / Real(3) * s_n * c.overlap - Real(alpha) * std::sqrt(c.m_eq * s_n) * c.v_n;
    f.normal = clamp ? max(fn, Real(0)) : fn;
    const Real fn_abs = f.normal < 0 ? -f.normal : f.normal;
    const Real beta_t = Real(alpha) * std::sqrt(tangential_mass(c.m_eq) * k_t);
    f.tangent = tangential_spring(c.normal, c.v_t, k_t, beta_t, Real(mu) * fn_abs, c.dt, hist);
    // the rolling spring's k_n is the secant stiffness F_n / delta = (2/3) S_n, as LIGGGHTS' epsd takes it
    f.torque = rolling.template torque<Rolls>(c, fn_abs, Real(2) / Real(3) * s_n, hist + history);
    if constexpr (Cohesive) f.normal -= cohesion.force(c.r_eff, c.overlap);
    // apart, or across a gap within the cohesion's range: the attraction alone, history cleared
    return touching_only<Cohesive, history + rolling_history<Rolls>>(f, c, cohesion, hist);
  }
};

}  // namespace spreadmap
