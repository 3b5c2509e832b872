// contact/hooke_history: linear spring-dashpot normal force parametrised as the study's (see
// hooke_slider.hpp: K_n = m_eq V_max^2/Delta_max^2, beta_n from eps, optional clamp and correction)
// with a Cundall-Strack tangential spring instead of the slider:
//
//   F_t = -k_t s - beta_t v_t, |F_t| <= mu |F_n|,   s += v_t dt (rotated into the tangent plane each step)
//   k_t = kappa K_n (kappa = tangential_stiffness_ratio, 2/7 by default),
//   beta_t = 2 zeta sqrt(k_t m_t), m_t = (2/7) m_eq: the tangential oscillation has the same damping ratio
//   as the normal one, and with kappa = 2/7 also the same frequency V_max/Delta_max.
//
// This is the physics of LIGGGHTS' hooke/stiffness with tangential history (and LAMMPS
// gran/hooke/history): a stuck contact holds a static tangential force, so nothing creeps.
// Reference: Cundall & Strack 1979; LAMMPS pair gran/hooke/history (slip reset of the spring).
// Assumptions: spheres; F_n unclamped unless clamp_normal; the cap uses |F_n| of the repulsion.
// Optional rolling resistance: a constant torque or the rolling spring (epsd; docs/rolling.md).
// Optional cohesion (SJKR, DMT or JKR pull-off in contact, van der Waals across a gap; contact_parts.hpp,
// docs/cohesion.md), subtracted from F_n. Units SI. History: 3 values per contact, the spring elongation s [m] in the
// global frame.
#pragma once
#include <spreadmap/contact.hpp>
#include <spreadmap/contact_parts.hpp>

#include <cmath>

namespace spreadmap {

struct HookeHistory {
  static constexpr sm_param_v1 params[] = {
      param_v_max,
      param_overlap_max,
      param_restitution,
      param_friction,
      number("tangential_stiffness_ratio", "-", 1e-3, 10, 2.0 / 7.0,
             "kappa = k_t / K_n: tangential spring stiffness relative to the normal one (2/7: equal frequencies)"),
      param_clamp_normal,
      param_clamp_correction,
      param_rolling_friction,
      param_rolling_model,
      param_rolling_damping,
      param_cohesion_energy_density,
      param_surface_energy,
      param_pull_off,
      param_hamaker_constant,
      param_vdw_min_gap,
      param_vdw_cutoff,
  };
  static constexpr int history = 3;
  static constexpr bool history_mirrors = true;  // the spring's elongation, a global vector: -s seen from j

  LinearNormal normal;
  double mu;
  double kappa;         // k_t / K_n
  double tangent_rate;  // beta_t / m_eq = 2 zeta omega0 sqrt(kappa 2/7) [1/s]
  Rolling rolling;
  Cohesion cohesion;

  static HookeHistory bind(const Values &v) {
    const LinearNormal n = LinearNormal::bind(v);
    const double kappa = v["tangential_stiffness_ratio"];
    return {n,
            v["friction"],
            kappa,
            2 * n.zeta * n.omega0 * std::sqrt(kappa * 2.0 / 7.0),
            Rolling::bind(v),
            Cohesion::bind(v)};
  }

  // The tangential mode (k_t over m_t) is the faster one when kappa > 2/7. The SJKR softening only slows
  // the normal mode, unless it cancels K_n.
  double natural_frequency(double m_eq, double r_eff) const {
    if (normal.collapses_under(cohesion, m_eq, r_eff)) return no_stable_step;
    const double rolling_mode = rolling.natural_frequency(m_eq * normal.omega0 * normal.omega0, m_eq);
    return max(normal.omega0 * std::sqrt(max(1.0, kappa * 3.5)), rolling_mode);
  }
  double damping_ratio(double, double) const { return normal.zeta; }
  bool makes_torque() const { return mu > 0 || rolling.mu_r > 0; }

  // Without the rolling spring (Law::history values in hist); the loops reach it through in_loop_form.
  template <class Real> SM_HD ContactForce<Real> operator()(const ContactState<Real> &c, Real *hist) const {
    return cohesion.on ? force<true, RollingForm::constant>(c, hist) : force<false, RollingForm::constant>(c, hist);
  }
  // hist: the tangential spring's 3 values, then the rolling spring's 3 (Spring).
  template <bool Cohesive, RollingForm Rolls, class Real>
  SM_HD ContactForce<Real> force(const ContactState<Real> &c, Real *hist) const {
    ContactForce<Real> f;
    f.normal = normal.force(c.m_eq, c.overlap, c.v_n);
    const Real fn_abs = f.normal < 0 ? -f.normal : f.normal;
    const Real w = Real(normal.omega0);
    const Real k_t = Real(kappa) * c.m_eq * w * w;
    f.tangent = tangential_spring(c.normal, c.v_t, k_t, c.m_eq * Real(tangent_rate), Real(mu) * fn_abs, c.dt, hist);
    f.torque = rolling.template torque<Rolls>(c, fn_abs, c.m_eq * w * w, hist + history);
    if constexpr (Cohesive) f.normal -= cohesion.force(c.r_eff, c.overlap);
    // apart, or across a gap within the cohesion's range: the attraction alone, history cleared
    return touching_only<Cohesive, history + rolling_history<Rolls>>(f, c, cohesion, hist);
  }
};

}  // namespace spreadmap
