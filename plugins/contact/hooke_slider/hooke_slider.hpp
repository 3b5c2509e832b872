// contact/hooke_slider: the reference study's model (its Eq. 1-4), a linear spring-dashpot in the
// normal direction and a Coulomb slider without tangential spring.
//
//   F_n = K_n delta - beta_n v_n,  K_n = m_eq V_max^2 / Delta_max^2,
//   beta_n = -2 ln(eps) sqrt(K_n m_eq / (pi^2 + ln^2 eps)) = 2 zeta sqrt(K_n m_eq)
//   F_t = -mu |F_n| e_t,           e_t = v_t / |v_t| (slip at the contact point, spin included)
//
// Every contact therefore has the natural frequency omega0 = V_max/Delta_max whatever the sizes
// (defaults 0.5 m/s and 2.5 um: omega0 = 2e5 rad/s, K_n = 724.857 N/m between two 250 um Ti-6Al-4V
// spheres and 1449.71 N/m against a wall, contact time pi/omega_d = 1.5748e-5 s at eps = 0.8).
// Assumptions: spheres, cohesionless by default; the force is not clamped by default (the study's Eq. 3 and the
// LIGGGHTS peer runs), so the dashpot may pull at the end of a contact and the isolated collision
// rebounds with exactly eps; |F_n| in the slider keeps friction active during that tail. Options:
// clamp_normal (F_n >= 0; restitution becomes exp(-2 zeta acos zeta / sqrt(1 - zeta^2))) and
// clamp_correction (damping solved at bind() so the clamped contact still returns eps).
// Zero slip (slider): stick (default) limits the force to m_t |v_t| / (2 dt), m_t = (2/7) m_eq, which
// removes half the slip per step below the Coulomb cap; viscous is LIGGGHTS' min(mu|F_n|, m_eq gamma_t
// |v_t|) (gamma_t = beta_n/m_eq by default; note (7/2) gamma_t dt must stay below 2); coulomb is the
// textbook slider with no force below slip_speed_min, which chatters: each step the slip reverses
// and full friction acts in alternate directions while a contact should be stuck; it takes a slip
// within the round-off of the normal speed for none (slip_round_off): a head-on impact has no
// friction, even with slip_speed_min = 0.
// Optional rolling resistance: a constant torque or the rolling spring (epsd; docs/rolling.md).
// Optional cohesion (SJKR, DMT or JKR pull-off in contact, van der Waals across a gap; contact_parts.hpp,
// docs/cohesion.md), subtracted from F_n after the slider and the rolling torque took |F_n| of the
// repulsion (LIGGGHTS' tangential_reduce off).
// References: the reference study (its Eq. 1-4); Cundall & Strack 1979. Units SI.
// History: none.
#pragma once
#include <spreadmap/contact.hpp>
#include <spreadmap/contact_parts.hpp>

namespace spreadmap {

struct HookeSlider {
  static constexpr sm_param_v1 params[] = {
      param_v_max,
      param_overlap_max,
      param_restitution,
      param_friction,
      enumeration(
          "slider", "stick|viscous|coulomb", "stick",
          "zero-slip handling: stick (half the slip removed per step), viscous (LIGGGHTS), coulomb (threshold)"),
      number("slip_damping", "1/s", 0, 1e12, 0,
             "gamma_t: viscous slider rate, F_t = -min(mu|F_n|, m_eq gamma_t |v_t|); 0 = beta_n/m_eq as LIGGGHTS"),
      number("slip_speed_min", "m/s", 0, 1, 1e-6, "coulomb slider: no tangential force while |v_t| <= this slip speed"),
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
  static constexpr int history = 0;
  // The slider is compiled into the loops (its own forms, contact.hpp): a loop computes only its slider's
  // force, without the divide of the stick slider for the others.
  static constexpr int own_forms = 3;
  int own_form() const { return int(slider); }

  LinearNormal normal;
  double mu;  // sliding friction
  Slider slider;
  double slip_rate;       // gamma_t [1/s]
  double slip_speed_min;  // [m/s]
  Rolling rolling;
  Cohesion cohesion;

  static HookeSlider bind(const Values &v) {
    const LinearNormal n = LinearNormal::bind(v);
    const double gamma = v["slip_damping"] > 0 ? v["slip_damping"] : 2 * n.zeta * n.omega0;
    return {n,
            v["friction"],
            slider_from_name(v.str("slider")),
            gamma,
            v["slip_speed_min"],
            Rolling::bind(v),
            Cohesion::bind(v)};
  }

  // The SJKR softening only slows the contact (the step stays the one for omega0) unless it cancels K_n.
  double natural_frequency(double m_eq, double r_eff) const {
    if (normal.collapses_under(cohesion, m_eq, r_eff)) return no_stable_step;
    return max(normal.omega0, rolling.natural_frequency(m_eq * normal.omega0 * normal.omega0, m_eq));
  }
  double damping_ratio(double, double) const { return normal.zeta; }
  bool makes_torque() const { return mu > 0 || rolling.mu_r > 0; }

  // Without the rolling spring (Law::history values in hist); the loops reach it through in_loop_form.
  template <class Real> SM_HD ContactForce<Real> operator()(const ContactState<Real> &c, Real *hist) const {
    return cohesion.on ? force<true, RollingForm::constant, any_own_form>(c, hist)
                       : force<false, RollingForm::constant, any_own_form>(c, hist);
  }
  template <bool Cohesive, RollingForm Rolls, int Own, class Real>
  SM_HD ContactForce<Real> force(const ContactState<Real> &c, Real *hist) const {
    // No branch on the contact (selects only; overlap <= 0 gives zeros), so that loops over contacts vectorise.
    // The rolling spring's form keeps history and is not vectorised: it may branch.
    ContactForce<Real> f;
    const bool touching = c.overlap > 0;
    const Real fn = normal.force(c.m_eq, c.overlap, c.v_n);
    f.normal = touching ? fn : Real(0);
    const Real fn_abs = f.normal < 0 ? -f.normal : f.normal;
    const Real round_off = slip_round_off(c.v_n < 0 ? -c.v_n : c.v_n);
    const Slider kind = Own == any_own_form ? slider : Slider(Own);  // a constant in a loop's own form
    f.tangent =
        slider_force(kind, Real(mu) * fn_abs, c.v_t, c.m_eq, c.dt, Real(slip_rate), Real(slip_speed_min), round_off);
    if constexpr (Rolls == RollingForm::spring) {
      const Real w = Real(normal.omega0);
      if (touching) f.torque = rolling.template torque<Rolls>(c, fn_abs, c.m_eq * w * w, hist);
      else rolling.template clear<Rolls>(hist);
    } else {
      f.torque = rolling.template torque<Rolls>(c, fn_abs, Real(0), hist);
    }
    if constexpr (Cohesive)
      f.normal -= touching ? cohesion.force(c.r_eff, c.overlap) : cohesion.gap_force(c.r_eff, c.overlap);
    return f;
  }
};

}  // namespace spreadmap
