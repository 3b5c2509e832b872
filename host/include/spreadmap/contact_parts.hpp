// Shared pieces of contact laws, composed by the plugins in plugins/contact/ (never copied):
//   - restitution -> damping ratio of a linear spring-dashpot, with the eps = 0 and eps = 1 limits,
//     and the restitution a clamped (F_n >= 0) dashpot actually gives;
//   - LinearNormal: the study's normal force K_n = m_eq (V_max/Delta_max)^2, beta_n from eps,
//     optionally clamped and optionally corrected so that the clamped contact still returns eps;
//   - Coulomb slider variants (stick, viscous, coulomb) for laws without a tangential spring;
//   - a Cundall-Strack tangential spring with Coulomb cap (history of 3 values);
//   - rolling resistance: a constant directional torque (Ai et al. 2011 model A) or an elastic-plastic
//     spring-dashpot (model C, EPSD; history of 3 values), chosen per instance;
//   - cohesion (SJKR, DMT and JKR pull-off) acting while in contact, off unless a scene asks for it.
// SI units throughout. The SM_HD parts follow hd.hpp's rules; bind helpers are host-only.
#pragma once
#include <spreadmap/contact.hpp>
#include <spreadmap/hd.hpp>
#include <spreadmap/params.hpp>

#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

namespace spreadmap {

// ---------------------------------------------------------------- restitution and damping ratio

// Damping ratio zeta of a linear spring-dashpot whose unclamped collision rebounds with restitution
// eps: zeta = -ln eps / sqrt(pi^2 + ln^2 eps). Limits taken exactly: eps = 0 gives critical damping
// (1, where the literal formula is inf/inf), eps = 1 gives exactly 0.
SM_HD double damping_ratio_from_restitution(double eps) {
  if (!(eps > 0)) return 1.0;
  if (eps >= 1) return 0.0;
  const double l = std::log(eps);
  return -l / std::sqrt(pi * pi + l * l);
}

// Restitution of a linear spring-dashpot collision when the force is clamped to F_n >= 0: the bodies
// separate when the force first vanishes (x'' = 0), which for damping ratio zeta < 1 happens at
// omega_d t = pi - 2 asin(zeta) = 2 acos(zeta), giving e_c = exp(-2 zeta acos(zeta) / sqrt(1 - zeta^2)).
// It tends to e^-2 at zeta = 1 and continues for zeta > 1 as exp(-2 zeta acosh(zeta) / sqrt(zeta^2 - 1)).
SM_HD double clamped_restitution(double zeta) {
  if (!(zeta > 0)) return 1.0;
  if (zeta == 1.0) return std::exp(-2.0);
  if (zeta < 1.0) return std::exp(-2.0 * zeta * std::acos(zeta) / std::sqrt(1.0 - zeta * zeta));
  return std::exp(-2.0 * zeta * std::acosh(zeta) / std::sqrt(zeta * zeta - 1.0));
}

// A number for an error message (std::to_string would export libstdc++ template symbols from a plugin).
inline std::string number_text(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", x);
  return text;
}

// Largest damping ratio the clamp correction may ask for; its clamped restitution is 2.5e-5.
inline constexpr double max_corrected_damping_ratio = 100.0;

// Host only: the damping ratio whose clamped collision rebounds with restitution eps (inverse of
// clamped_restitution, by bisection; e_c decreases monotonically in zeta). eps = 0 would need
// infinite damping, so values below clamped_restitution(max_corrected_damping_ratio) are refused.
inline double damping_ratio_for_clamped_restitution(double eps) {
  if (eps >= 1) return 0.0;
  if (eps < clamped_restitution(max_corrected_damping_ratio))
    throw ParamError("restitution " + number_text(eps) +
                     " cannot be reached with clamp_correction (it needs unbounded damping); use restitution >= " +
                     number_text(clamped_restitution(max_corrected_damping_ratio)) + " or clamp_correction: false");
  double lo = 0, hi = max_corrected_damping_ratio;
  for (int k = 0; k < 200 && hi - lo > 1e-15 * hi; ++k) {
    const double mid = 0.5 * (lo + hi);
    (clamped_restitution(mid) > eps ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

// Effective mass of the tangential slip of two solid spheres (or a sphere and a wall) including
// their rotation: an impulse J changes the slip by J (1 + 5/2) / m_eq, so m_t = (2/7) m_eq.
template <class Real> SM_HD Real tangential_mass(Real m_eq) { return Real(2) / Real(7) * m_eq; }

// ---------------------------------------------------------------- linear normal force (the study's)

// Schema entries shared by the Hooke laws (listed in each law's params[]).
inline constexpr sm_param_v1 param_v_max =
    number("v_max", "m/s", 1e-4, 1e3, 0.5,
           "V_max: largest expected impact speed; with overlap_max sets K_n = m_eq V_max^2 / Delta_max^2");
inline constexpr sm_param_v1 param_overlap_max =
    number("overlap_max", "m", 1e-12, 1e-2, 2.5e-6,
           "Delta_max: overlap reached at an undamped impact at V_max (1 % of 250 um by default)");
inline constexpr sm_param_v1 param_restitution =
    number("restitution", "-", 0, 1, 0.8, "epsilon: normal coefficient of restitution of an isolated collision");
inline constexpr sm_param_v1 param_friction =
    number("friction", "-", 0, 10, 0.185, "mu: sliding (Coulomb) friction coefficient, |F_t| <= mu |F_n|");
inline constexpr sm_param_v1 param_rolling_friction = number(
    "rolling_friction", "-", 0, 1, 0, "mu_r: rolling resistance, torque mu_r r_eff |F_n| against the relative rolling");
inline constexpr sm_param_v1 param_rolling_model =
    enumeration("rolling_model", "constant|epsd", "constant",
                "rolling resistance: constant (a torque mu_r r_eff |F_n| against the rolling) or epsd (a rolling "
                "spring k_r = 2.25 k_n mu_r^2 r_eff^2 limited at mu_r r_eff |F_n|, with a dashpot; the sphere rests)");
inline constexpr sm_param_v1 param_rolling_damping =
    number("rolling_damping", "-", 0, 2, 0.3,
           "eta_r: epsd's dashpot, C_r = eta_r 2 sqrt(I_r k_r) with I_r = (7/5) m_eq r_eff^2 (off at the limit)");
inline constexpr sm_param_v1 param_clamp_normal = boolean(
    "clamp_normal", false,
    "clamp F_n >= 0 (no attraction at the end of a damped contact); raises the restitution unless clamp_correction");
inline constexpr sm_param_v1 param_clamp_correction = boolean(
    "clamp_correction", false,
    "with clamp_normal: choose the damping so that the clamped contact still rebounds with restitution epsilon");

struct Cohesion;  // below

// F_n = m_eq (omega0^2 delta - 2 zeta omega0 v_n): K_n = m_eq omega0^2 with omega0 = V_max/Delta_max,
// beta_n = 2 zeta sqrt(K_n m_eq) = -2 ln eps sqrt(K_n m_eq / (pi^2 + ln^2 eps)). The dashpot opposes the
// relative normal motion (v_n < 0 approaching makes it repulsive).
struct LinearNormal {
  double omega0;  // V_max / Delta_max [rad/s], the same for every contact whatever the sizes
  double zeta;    // damping ratio actually used (corrected when clamp_correction)
  bool clamp;     // F_n >= 0

  static LinearNormal bind(const Values &v) {
    const double eps = v["restitution"];
    const bool clamp = v.boolean("clamp_normal"), correct = v.boolean("clamp_correction");
    if (correct && !clamp) throw ParamError("clamp_correction: true needs clamp_normal: true");
    const double zeta = correct ? damping_ratio_for_clamped_restitution(eps) : damping_ratio_from_restitution(eps);
    return {v["v_max"] / v["overlap_max"], zeta, clamp};
  }
  // True when a cohesion's softening cancels this spring, K_n = m_eq omega0^2, for these particles.
  bool collapses_under(const Cohesion &c, double m_eq, double r_eff) const;
  // Normal force along the normal, > 0 repulsive [N].
  template <class Real> SM_HD Real force(Real m_eq, Real overlap, Real v_n) const {
    const Real w = Real(omega0);
    const Real f = m_eq * w * (w * overlap - Real(2 * zeta) * v_n);
    return clamp ? max(f, Real(0)) : f;
  }
};

// ---------------------------------------------------------------- Coulomb slider (no spring)

// What the slider does where the slip direction is undefined (vanishing slip).
enum class Slider : int {
  stick = 0,    // -min(mu|F_n|, m_t |v_t| / (2 dt)) e_t: below the cap it removes half the slip per step
  viscous = 1,  // -min(mu|F_n|, m_eq gamma_t |v_t|) e_t: LIGGGHTS' regularised slider
  coulomb = 2   // -mu|F_n| e_t when |v_t| > slip_speed_min, else 0 (chatters around zero slip)
};

inline Slider slider_from_name(const std::string &name) {
  if (name == "stick") return Slider::stick;
  if (name == "viscous") return Slider::viscous;
  if (name == "coulomb") return Slider::coulomb;
  throw ParamError("slider '" + name + "' is not one of stick, viscous, coulomb");
}

// Machine epsilon of Real (std::numeric_limits is host-only under nvcc).
template <class Real> SM_HD constexpr Real machine_epsilon() {
  return sizeof(Real) == sizeof(float) ? Real(1.1920928955078125e-7) : Real(2.220446049250313e-16);
}

// The slip a contact's kinematics make from round-off alone: along the line of centres v - (v.n) n is
// not zero but a few ulps of v_n, since the normal d/|d| is off by an ulp or so. Such a slip has no
// direction: taken as one, the coulomb slider (full mu |F_n| for any slip above slip_speed_min) would
// brake a head-on impact (restitution 0.478 for 0.5), so it takes a slip up to slip_round_off(|v_n|)
// for none. The stick and viscous sliders give a round-off slip a round-off force, proportional to
// it: they are left as they are (a resting heap's contacts have such slips; their bits stay).
inline constexpr double slip_round_off_ulps = 8;
template <class Real> SM_HD Real slip_round_off(Real normal_speed) {
  return Real(slip_round_off_ulps) * machine_epsilon<Real>() * normal_speed;
}

// Tangential force of a spring-less slider with Coulomb cap `cap` = mu |F_n| [N].
// slip_rate: gamma_t [1/s] (viscous); slip_speed_min [m/s] (coulomb); round_off [m/s] (coulomb): no
// force for a slip up to this speed either (slip_round_off).
// Written with selects, no branch, so that a loop over contacts vectorises.
template <class Real>
SM_HD Vec3<Real> slider_force(Slider kind, Real cap, const Vec3<Real> &v_t, Real m_eq, Real dt, Real slip_rate,
                              Real slip_speed_min, Real round_off = Real(0)) {
  const Real speed = norm(v_t);
  // Stick: below the cap, the impulse F dt changes the slip by F dt / m_t = |v_t| / 2: never reverses
  // it, and a round-off slip gets a round-off force (no spurious spin). Every case is computed and one
  // selected: under -ftrapping-math (a plugin built without the SDK's options) a compiler may not
  // evaluate a division of a branch not taken.
  const Real stick = tangential_mass(m_eq) * speed / (Real(2) * dt), viscous = m_eq * slip_rate * speed;
  const Real magnitude = min(cap, kind == Slider::stick ? stick : (kind == Slider::viscous ? viscous : cap));
  const Real scale = -magnitude / speed;
  const bool acts =
      (speed > 0) & (cap > 0) & !((kind == Slider::coulomb) & ((speed <= slip_speed_min) | (speed <= round_off)));
  return {acts ? v_t.x * scale : Real(0), acts ? v_t.y * scale : Real(0), acts ? v_t.z * scale : Real(0)};
}

// ---------------------------------------------------------------- tangential spring (history 3)

// Cundall-Strack tangential spring with Coulomb cap. hist[0..2] is the spring's elongation vector s
// [m] in the global frame, rotated each step into the current tangent plane (length kept) before
// v_t dt is added. F_t = -k_t s - damping v_t, capped at `cap`; when capped, s is reset to the
// elongation consistent with the capped force (as LAMMPS gran/hooke/history does).
template <class Real>
SM_HD Vec3<Real> tangential_spring(const Vec3<Real> &normal, const Vec3<Real> &v_t, Real stiffness, Real damping,
                                   Real cap, Real dt, Real *hist) {
  Vec3<Real> s{hist[0], hist[1], hist[2]};
  const Real before = norm(s);
  s -= normal * dot(s, normal);
  const Real after = norm(s);
  s *= after > 0 ? before / after : Real(1);  // selects, no branch (x 1 is exact): a queue vectorises
  s += v_t * dt;
  Vec3<Real> f = -(s * stiffness) - v_t * damping;
  const Real magnitude = norm(f);
  const bool capped = magnitude > cap;
  f *= capped ? cap / magnitude : Real(1);
  const Vec3<Real> slipped = -(f + v_t * damping) * (Real(1) / stiffness);
  hist[0] = capped ? slipped.x : s.x;
  hist[1] = capped ? slipped.y : s.y;
  hist[2] = capped ? slipped.z : s.z;
  return f;
}

// What a law with history returns where the bodies do not touch (overlap <= 0: a gap its cohesion
// reaches across): the attraction alone, no friction or rolling, and its `History` values cleared. The
// law computes its touching answer `f` for every contact (NaN where it does not touch: harmless, not
// trapped) and this selects, so that a queue's loop has no branch and vectorises.
template <bool Cohesive, int History, class Real, class Attraction>
SM_HD ContactForce<Real> touching_only(const ContactForce<Real> &f, const ContactState<Real> &c,
                                       const Attraction &cohesion, Real *hist) {
  const bool touching = c.overlap > 0;
  for (int q = 0; q < History; ++q) hist[q] = touching ? hist[q] : Real(0);
  Real apart = 0;
  if constexpr (Cohesive) apart = -cohesion.gap_force(c.r_eff, c.overlap);
  const Real zero = 0;
  return {touching ? f.normal : apart,
          {touching ? f.tangent.x : zero, touching ? f.tangent.y : zero, touching ? f.tangent.z : zero},
          {touching ? f.torque.x : zero, touching ? f.torque.y : zero, touching ? f.torque.z : zero}};
}

// ---------------------------------------------------------------- rolling resistance

// Constant directional torque (Ai et al. 2011, model A): M_r = -mu_r r_eff |F_n| w_r/|w_r| with w_r the
// relative angular velocity projected on the tangent plane (rolling; twisting is left free).
// Where the rolling speed vanishes the direction is undefined; instead of a threshold the magnitude is
// limited, as the stick slider is, to what removes at most half of w_r per step for the smallest
// relative inertia of the pair, I_r = (2/5) m_eq r_eff^2 (exact against a wall, a lower bound for two
// spheres): no chatter, and a sphere that stops rolling stays stopped.
template <class Real>
SM_HD Vec3<Real> rolling_torque(Real mu_r, Real r_eff, Real fn_abs, const Vec3<Real> &normal, const Vec3<Real> &w_rel,
                                Real m_eq, Real dt) {
  if (!(mu_r > 0)) return {0, 0, 0};  // the same for every contact of a law: no obstacle to vectorising
  const Vec3<Real> w = w_rel - normal * dot(w_rel, normal);
  const Real speed = norm(w);
  const Real inertia = Real(0.4) * m_eq * r_eff * r_eff;
  const Real magnitude = min(mu_r * r_eff * fn_abs, inertia * speed / (Real(2) * dt));
  const Real scale = -magnitude / speed;
  const bool acts = speed > 0;  // selects, no branch: vectorises
  return {acts ? w.x * scale : Real(0), acts ? w.y * scale : Real(0), acts ? w.z * scale : Real(0)};
}

// Clears a contact's history (apart, or no history).
template <class Real> SM_HD void clear_history(Real *hist, int n) {
  for (int q = 0; q < n; ++q) hist[q] = 0;
}

// The rolling part a law holds (`Rolling rolling`): the constant torque above, or the elastic-plastic
// spring-dashpot (EPSD, Ai et al. 2011 model C, as LIGGGHTS' rolling_friction epsd): a rolling spring
// M_k, kept in the global frame in 3 values of history after the law's own and turned into the
// current tangent plane each step, loaded by the relative rolling, M_k -= k_r w_r dt with
// k_r = 2.25 k_n mu_r^2 r_eff^2 (k_n the law's normal stiffness, F_n / delta), and limited at
// M_m = mu_r r_eff |F_n|; a dashpot M_d = -eta_r 2 sqrt(I_r k_r) w_r, I_r = (7/5) m_eq r_eff^2 (a sphere
// rolling on a wall), acts below the limit only. Under a torque below M_m a sphere turns by the
// elastic angle T / k_r and rests there; above it, it rolls against M_m. The choice is made per
// instance: the loops are compiled without rolling friction, with the constant torque and with the
// spring (RollingForm, LoopForm in contact.hpp), so a law without the spring runs the code and bits it
// always ran, and one without rolling friction none of it. Host side: bind(); SM_HD: the torques.
struct Rolling {
  static constexpr int history = rolling_spring_history;  // of the spring; none for the constant torque
  double mu_r;
  bool spring;     // epsd
  double damping;  // eta_r

  static Rolling bind(const Values &v) {
    const bool epsd = v.str("rolling_model") == "epsd";
#if SPREADMAP_TARGET_ABI_MINOR < 1
    if (epsd)
      throw ParamError("rolling_model epsd needs plugin ABI 10.1 (history per instance); this plugin targets 10.0: "
                       "rebuild it without SPREADMAP_TARGET_ABI_MINOR");
#endif
    return {v["rolling_friction"], epsd && v["rolling_friction"] > 0, v["rolling_damping"]};
  }
  // The stiffest rolling mode [rad/s]: k_r against the smallest relative inertia (2/5) m_eq r_eff^2 (r_eff
  // cancels); 0 without the spring. k_n: the law's normal stiffness at the step's reference overlap [N/m].
  double natural_frequency(double k_n, double m_eq) const {
    if (!spring) return 0;
    return std::sqrt(2.25 * k_n * mu_r * mu_r / (0.4 * m_eq));
  }

  // Torque on i [N m]. The spring: hist holds its 3 values (after the law's).
  template <RollingForm Rolls, class Real>
  SM_HD Vec3<Real> torque(const ContactState<Real> &c, Real fn_abs, Real k_n, Real *hist) const {
    if constexpr (Rolls == RollingForm::none) {
      return {0, 0, 0};
    } else if constexpr (Rolls == RollingForm::constant) {
      return rolling_torque(Real(mu_r), c.r_eff, fn_abs, c.normal, c.w_rel, c.m_eq, c.dt);
    } else {
      const Vec3<Real> w = c.w_rel - c.normal * dot(c.w_rel, c.normal);
      Vec3<Real> m{hist[0], hist[1], hist[2]};
      const Real before = norm(m);
      m -= c.normal * dot(m, c.normal);  // into the current tangent plane, its size kept
      const Real after = norm(m);
      if (after > 0) m *= before / after;
      const Real k_r = Real(2.25 * mu_r * mu_r) * k_n * c.r_eff * c.r_eff;
      m -= w * (k_r * c.dt);
      const Real limit = Real(mu_r) * c.r_eff * fn_abs, size = norm(m);
      const bool mobilised = size > limit;
      m *= mobilised ? (size > 0 ? limit / size : Real(0)) : Real(1);  // selects: a queue vectorises
      hist[0] = m.x;
      hist[1] = m.y;
      hist[2] = m.z;
      const Real inertia = Real(1.4) * c.m_eq * c.r_eff * c.r_eff;
      const Vec3<Real> damped = m - w * (Real(2 * damping) * std::sqrt(inertia * k_r));
      return {mobilised ? m.x : damped.x, mobilised ? m.y : damped.y, mobilised ? m.z : damped.z};
    }
  }
  // Clears the spring (the contact ended).
  template <RollingForm Rolls, class Real> SM_HD void clear(Real *hist) const {
    if constexpr (Rolls == RollingForm::spring) clear_history(hist, history);
  }
};

// ---------------------------------------------------------------- cohesion (in contact and across a gap)

// Schema entries of the cohesion part, one group added to every law's params[]. Each value stands on its
// own (0 = none), so no combination is refused; the attractions add up where several are set.
// k_c's range ends where the Hooke laws' contact of two 200 um spheres would collapse (see outweighs());
// it covers the values used with LIGGGHTS' cohesion sjkr (1e4 to 3e5 J/m^3).
inline constexpr sm_param_v1 param_cohesion_energy_density =
    number("cohesion_energy_density", "J/m^3", 0, 5e5, 0,
           "k_c: SJKR cohesion, attraction k_c A in contact with A = 2 pi r_eff delta (0: none)");
inline constexpr sm_param_v1 param_surface_energy =
    number("surface_energy", "J/m^2", 0, 10, 0,
           "gamma: surface energy, a constant attraction in contact equal to the pull-off force (0: none)");
inline constexpr sm_param_v1 param_pull_off = enumeration(
    "pull_off", "dmt|jkr", "dmt", "pull-off force of surface_energy: dmt 2 pi gamma r_eff, jkr 1.5 pi gamma r_eff");
inline constexpr sm_param_v1 param_hamaker_constant =
    number("hamaker_constant", "J", 0, 1e-17, 0,
           "A: van der Waals attraction A r_eff / (6 s^2) across a gap s up to vdw_cutoff, held at its value at "
           "vdw_min_gap closer in and in contact (0: none; CPU only)");
inline constexpr sm_param_v1 param_vdw_min_gap =
    number("vdw_min_gap", "m", 1e-11, 1e-5, 4e-10,
           "s_0: the gap below which the van der Waals force stays at A r_eff / (6 s_0^2) (it would diverge)");
inline constexpr sm_param_v1 param_vdw_cutoff =
    number("vdw_cutoff", "m", 0, 1e-4, 1e-6,
           "s_c: the gap beyond which the van der Waals force is cut to 0; the engine lists pairs this much farther");

// Attractive normal force (> 0 pulls the bodies together), subtracted from the law's repulsion.
// In contact (delta > 0):
//   SJKR:         F_c = k_c A,             A = 2 pi r_eff delta (the overlap's intersection circle to first
//                                          order in delta/r; LIGGGHTS' cohesion sjkr takes the exact lens)
//   surface energy, pull_off: dmt  F_c = 2 pi gamma r_eff   (the DMT pull-off force, constant)
//                   pull_off: jkr  F_c = 1.5 pi gamma r_eff (the JKR pull-off force, constant; not the JKR
//                                                            force-overlap curve)
//   van der Waals: F_c = A r_eff / (6 s_0^2) (the gap force at s_0, constant)
// One formula, F_c = r_eff (area_rate delta + pull_off_rate), covers them. Across a gap s = -delta only the van der
// Waals force acts (Hamaker's sphere-sphere and sphere-plane force for s << r, as Parteli and Poeschel 2016 used
// for powder spreading): F = r_eff A / (6 max(s, s_0)^2) for s < s_c, 0 beyond. It is continuous at contact and
// drops by (s_0/s_c)^2 of its contact value at the cut-off. A law with it declares range() = s_c: the engine
// then gives it pairs and plane records down to delta = -s_c (docs/cohesion.md).
// `on` is false when all are 0; the laws' loops are then compiled without this part (LoopForm in
// contact.hpp), so a scene without cohesion runs the very code and bits it ran before.
struct Cohesion {
  bool on;
  double area_rate;      // 2 pi k_c [N/m^2]
  double pull_off_rate;  // 2 pi gamma (dmt) or 1.5 pi gamma (jkr), plus A / (6 s_0^2) [N/m]
  double gap_rate;       // A / 6 [J]
  double min_gap;        // s_0 [m]
  double range;          // s_c when A > 0, else 0 [m]

  static Cohesion bind(const Values &v) {
    const double k_c = v["cohesion_energy_density"], gamma = v["surface_energy"];
    const double factor = v.str("pull_off") == "jkr" ? 1.5 : 2.0;
    const double a = v["hamaker_constant"], s0 = v["vdw_min_gap"], sc = v["vdw_cutoff"];
    if (a > 0 && !(sc > s0))
      throw ParamError("vdw_cutoff (" + number_text(sc) + " m) must exceed vdw_min_gap (" + number_text(s0) +
                       " m) for the van der Waals force to act across a gap: raise vdw_cutoff");
    const double contact_rate = a > 0 ? a / (6 * s0 * s0) : 0.0;
    return {
        k_c > 0 || gamma > 0 || a > 0, 2 * pi * k_c, factor * pi * gamma + contact_rate, a / 6, s0, a > 0 ? sc : 0.0};
  }
  // Attractive force [N] (> 0 pulls the bodies together) of a contact with this overlap (> 0).
  template <class Real> SM_HD Real force(Real r_eff, Real overlap) const {
    return r_eff * (Real(area_rate) * overlap + Real(pull_off_rate));
  }
  // Attractive force [N] across the gap -overlap (overlap <= 0); 0 at and beyond the cut-off. Selects only.
  template <class Real> SM_HD Real gap_force(Real r_eff, Real overlap) const {
    const Real s = max(-overlap, Real(min_gap));
    return -overlap < Real(range) ? r_eff * Real(gap_rate) / (s * s) : Real(0);
  }
  // How much the attraction softens the contact: -dF_c/d delta [N/m] (sjkr; 0 for the constant ones).
  double softening(double r_eff) const { return area_rate * r_eff; }
  // True when the softening cancels a linear spring of this stiffness [N/m]: the net force then
  // attracts at every overlap and the contact collapses at any step.
  bool outweighs(double stiffness, double r_eff) const { return softening(r_eff) >= stiffness; }
  // Work the attraction does while a contact closes from 0 to `overlap` [J].
  double work(double r_eff, double overlap) const {
    return r_eff * overlap * (0.5 * area_rate * overlap + pull_off_rate);
  }
};

inline bool LinearNormal::collapses_under(const Cohesion &c, double m_eq, double r_eff) const {
  return c.outweighs(m_eq * omega0 * omega0, r_eff);
}

// What natural_frequency returns where no step is stable (a law whose attraction outweighs its
// stiffness): an infinitely fast contact, whose critical step is 0; the host then refuses the scene.
inline constexpr double no_stable_step = std::numeric_limits<double>::infinity();

}  // namespace spreadmap
