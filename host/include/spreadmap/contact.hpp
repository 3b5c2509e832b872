// Contact laws: a trivially copyable functor of host-device code, instantiated by the SDK's loops
// inside the plugin. No virtual call per contact: the CPU engine calls the plugin once per queue of up
// to 64 contacts (evaluate_pairs, evaluate_walls), the CUDA backend once per step.
//
// A law provides:
//   static constexpr sm_param_v1 params[];        schema
//   static constexpr int history;                 values of history per contact (0 = none)
//   static Law bind(const sm::Values &);          host side: derive constants, may throw ParamError
//   double natural_frequency(double m_eq, double r_eff) const;  largest sqrt(K/m_eq) [rad/s]
//   double damping_ratio(double m_eq, double r_eff) const;      zeta of its dashpot at that stiffness
//   bool makes_torque() const;                    whether any tangential force or rolling torque exists
//   template <class Real> SM_HD ContactForce<Real> operator()(const ContactState<Real>&, Real *hist) const;
//   static constexpr bool history_mirrors = true;  optional, for a law with history whose every value,
//                                                 seen from the other body, is the negation (a vector
//                                                 of the contact in the global frame): each touching
//                                                 pair is then evaluated once (evaluate_pairs)
// and, with the cohesion part, `Cohesion cohesion` and force<Cohesive>() (see WithCohesion below). A law
// whose cohesion reaches across a gap (cohesion.range > 0) is given pairs and wall records down to
// overlap = -range, and must then return the attraction alone there (no repulsion, friction or history).
// A law whose operator() decides per contact with selects (a ? b : c on computed values) rather than
// branches runs on SIMD lanes when it evaluates a queue (evaluate_pairs below): a law without history,
// and one whose history mirrors (its queue then holds a contiguous copy of the history).
#pragma once
#include <spreadmap/batch.hpp>
#include <spreadmap/hd.hpp>
#include <spreadmap/plugin.hpp>
#include <spreadmap/simd.hpp>

#include <concepts>
#include <type_traits>

namespace spreadmap {

// Kinematics of one contact, seen from particle i (the one receiving the force).
template <class Real> struct ContactState {
  Vec3<Real> normal;  // unit, from the other body towards i
  Real overlap;       // > 0 [m]; down to -range for a law that reaches across a gap
  Real v_n;           // (v_i - v_other) . normal at the contact point [m/s]; < 0 approaching
  Vec3<Real> v_t;     // tangential relative velocity of i at the contact point [m/s]
  Vec3<Real> w_rel;   // w_i - w_other [rad/s] (rolling resistance)
  Real m_eq;          // m_i m_j / (m_i + m_j); the particle mass against a wall [kg]
  Real r_eff;         // r_i r_j / (r_i + r_j); the particle radius against a wall [m]
  Real dt;            // time step [s]
};

// Force on particle i. Its torque is arm x tangent with arm = -r_i normal, plus `torque`.
template <class Real> struct ContactForce {
  Real normal = 0;                 // along state.normal, > 0 repulsive [N]
  Vec3<Real> tangent = {0, 0, 0};  // [N]
  Vec3<Real> torque = {0, 0, 0};   // extra torque on i, e.g. rolling resistance [N m]
};

// The contact ops table, shared by every contact plugin.
typedef struct sm_contact_ops_v1 {
  uint32_t history;
  double (*natural_frequency)(const void *self, double m_eq, double r_eff);
  double (*damping_ratio)(const void *self, double m_eq, double r_eff);
  int (*makes_torque)(const void *self);
  void (*pairs_f64)(const void *self, const Particles<double> *p, const PairList<double> *list);
  void (*pairs_f32)(const void *self, const Particles<float> *p, const PairList<float> *list);
  void (*walls_f64)(const void *self, const Particles<double> *p, const WallContacts<double> *w);
  void (*walls_f32)(const void *self, const Particles<float> *p, const WallContacts<float> *w);
  double (*range)(const void *self);  // how far across a gap the law attracts [m]; 0: touching only
#if SPREADMAP_TARGET_ABI_MINOR >= 1
  // ABI 10.1: history values per contact of this instance (`history` is then the most any instance keeps).
  uint32_t (*history_of)(const void *self);
#endif
#if SPREADMAP_TARGET_ABI_MINOR >= 3
  // ABI 10.3: the CPU engine's loops hand the law queues of contacts (batch.hpp) and keep to themselves
  // how they walk the list and share it between threads. A host before 10.3 calls pairs_* and walls_*.
  void (*pair_queue_f64)(const void *self, const Particles<double> *p, const PairQueue<double> *q);
  void (*pair_queue_f32)(const void *self, const Particles<float> *p, const PairQueue<float> *q);
  void (*wall_queue_f64)(const void *self, const Particles<double> *p, const WallContacts<double> *w,
                         const WallQueue<double> *q);
  void (*wall_queue_f32)(const void *self, const Particles<float> *p, const WallContacts<float> *w,
                         const WallQueue<float> *q);
#endif
#if SPREADMAP_TARGET_ABI_MINOR >= 4
  // ABI 10.4: 1 when every history value the instance keeps mirrors (Law::history_mirrors; the rolling
  // spring's always does; none kept counts): the engine's pair queues then give it on_j.
  int (*history_mirrors)(const void *self);
#endif
} sm_contact_ops_v1;

// Minimum-image separation along one axis.
template <class Real> SM_HD Real wrap(Real d, Real length, bool periodic) {
  if (periodic) {
    if (d > Real(0.5) * length) d -= length;
    else if (d < Real(-0.5) * length) d += length;
  }
  return d;
}

// Adds the force and torque of one contact to particle i's running sums.
template <class Real>
SM_HD void accumulate(const ContactForce<Real> &f, const Vec3<Real> &normal, Real r_i, Vec3<Real> &force,
                      Vec3<Real> &torque) {
  force += normal * f.normal + f.tangent;
  torque += cross(normal * (-r_i), f.tangent) + f.torque;
}

// A law that may attract across a gap: a form with range() [m] (WithCohesion<Law, true>, below) or a
// law with the cohesion part (cohesion.range). Any other form (WithCohesion<Law, false>, a law without
// the part) is given touching contacts only, with the very instructions it always ran.
template <class Law>
concept ReachesAcrossGap = requires(const Law &law) {
  { law.range() } -> std::convertible_to<double>;
}
|| requires(const Law &law) {
  { law.cohesion.range } -> std::convertible_to<double>;
};
template <class Law> SM_HD double gap_range(const Law &law) {
  if constexpr (requires { law.range(); }) return law.range();
  else return law.cohesion.range;
}

// The centre distance below which particles i and j interact: touching, or within the law's range.
template <class Law, class Real> SM_HD Real interaction_reach(const Law &law, Real r_i, Real r_j) {
  if constexpr (ReachesAcrossGap<Law>) return r_i + r_j + Real(gap_range(law));
  else return r_i + r_j;
}

// The overlap above which a wall record interacts: 0 (touching), or down to the gap the records hold
// (WallContacts::gap) and the law reaches.
template <class Law, class Real> SM_HD Real interaction_floor(const Law &law, const WallContacts<Real> &w) {
  if constexpr (ReachesAcrossGap<Law>) return Real(0) - min(w.gap, Real(gap_range(law)));
  else return Real(0);
}

// The kinematics of the pair (i, j) within reach, seen from i; d = x_i - x_j (minimum image), dist2 = |d|^2.
template <class Real>
SM_HD ContactState<Real> pair_contact_state(const Particles<Real> &p, std::uint32_t i, std::uint32_t j,
                                            const Vec3<Real> &d, Real dist2) {
  const Real dist = std::sqrt(dist2);
  ContactState<Real> c;
  c.normal = d * (Real(1) / dist);
  c.overlap = (p.r[i] + p.r[j]) - dist;
  const Vec3<Real> vi{p.vx[i], p.vy[i], p.vz[i]}, wi{p.wx[i], p.wy[i], p.wz[i]};
  const Vec3<Real> vj{p.vx[j], p.vy[j], p.vz[j]}, wj{p.wx[j], p.wy[j], p.wz[j]};
  // velocity of i's surface relative to j's at the contact point
  const Vec3<Real> v = vi - vj - cross(wi * p.r[i] + wj * p.r[j], c.normal);
  c.v_n = dot(v, c.normal);
  c.v_t = v - c.normal * c.v_n;
  c.w_rel = wi - wj;
  c.m_eq = p.m[i] * p.m[j] / (p.m[i] + p.m[j]);
  c.r_eff = p.r[i] * p.r[j] / (p.r[i] + p.r[j]);
  c.dt = p.dt;
  return c;
}

// The forces on particle i from its neighbours, summed in list order and added to its accumulators:
// one GPU thread per particle under CUDA, and the whole-list loop of hosts before ABI 10.3. The CPU
// engine's queues give the same bits (each particle's contributions added in list order).
template <class Law, class Real>
SM_HD void pair_forces_on(const Law &law, const Particles<Real> &p, const PairList<Real> &list, std::uint32_t i) {
  const Real lx = p.box_hi[0] - p.box_lo[0], ly = p.box_hi[1] - p.box_lo[1], lz = p.box_hi[2] - p.box_lo[2];
  Vec3<Real> force{0, 0, 0}, torque{0, 0, 0};
  for (std::uint32_t k = list.start[i]; k < list.start[i + 1]; ++k) {
    const std::uint32_t j = list.nbr[k];
    Vec3<Real> d{wrap(p.x[i] - p.x[j], lx, p.periodic[0]), wrap(p.y[i] - p.y[j], ly, p.periodic[1]),
                 wrap(p.z[i] - p.z[j], lz, p.periodic[2])};
    const Real dist2 = dot(d, d), reach = interaction_reach(law, p.r[i], p.r[j]);
    Real *h = Law::history ? list.hist + std::size_t(k) * Law::history : nullptr;
    if (dist2 >= reach * reach) {
      for (int q = 0; q < Law::history; ++q) h[q] = 0;  // apart: forget
      continue;
    }
    const ContactState<Real> c = pair_contact_state(p, i, j, d, dist2);
    accumulate(law(c, h), c.normal, p.r[i], force, torque);
  }
  p.fx[i] += force.x;
  p.fy[i] += force.y;
  p.fz[i] += force.z;
  p.tx[i] += torque.x;
  p.ty[i] += torque.y;
  p.tz[i] += torque.z;
}

// The kinematics of particle i against a wall from its dense record (interacting: overlap above the floor).
template <class Real>
SM_HD ContactState<Real> wall_contact_state(const Particles<Real> &p, const WallContacts<Real> &w, std::uint32_t i) {
  ContactState<Real> c;
  c.normal = {w.nx[i], w.ny[i], w.nz[i]};
  c.overlap = w.overlap[i];
  const Vec3<Real> wi{p.wx[i], p.wy[i], p.wz[i]};
  const Vec3<Real> v =
      Vec3<Real>{p.vx[i] - w.vx[i], p.vy[i] - w.vy[i], p.vz[i] - w.vz[i]} - cross(wi * p.r[i], c.normal);
  c.v_n = dot(v, c.normal);
  c.v_t = v - c.normal * c.v_n;
  c.w_rel = wi;
  c.m_eq = p.m[i];
  c.r_eff = p.r[i];
  c.dt = p.dt;
  return c;
}

// The force of one wall on particle i from its dense record (nothing when not touching): one GPU
// thread per particle under CUDA, and the whole-wall loop of hosts before ABI 10.3.
template <class Law, class Real>
SM_HD void wall_force_on(const Law &law, const Particles<Real> &p, const WallContacts<Real> &w, std::uint32_t i) {
  Real *h = Law::history ? w.hist + std::size_t(i) * Law::history : nullptr;
  if (!(w.overlap[i] > interaction_floor(law, w))) {
    for (int q = 0; q < Law::history; ++q) h[q] = 0;
    return;
  }
  const ContactState<Real> c = wall_contact_state(p, w, i);
  Vec3<Real> force{0, 0, 0}, torque{0, 0, 0};
  accumulate(law(c, h), c.normal, p.r[i], force, torque);
  p.fx[i] += force.x;
  p.fy[i] += force.y;
  p.fz[i] += force.z;
  p.tx[i] += torque.x;
  p.ty[i] += torque.y;
  p.tz[i] += torque.z;
}

namespace detail {
// The six rows of a queue's output (force x, y, z, torque x, y, z, `stride` apart), as pointers taken once:
// stores through them are contiguous in the queue's index, which the vectoriser sees (an index computed
// as row * stride + q in 32 bits might wrap, and would be stored with scatters).
template <class Real> struct QueueRows {
  Real *row[6];
  QueueRows(Real *out, std::uint32_t stride) {
    for (int c = 0; c < 6; ++c) row[c] = out ? out + std::size_t(c) * stride : nullptr;
  }
  SM_HD void put(std::uint32_t q, const Vec3<Real> &f, const Vec3<Real> &t) const {
    row[0][q] = f.x;
    row[1][q] = f.y;
    row[2][q] = f.z;
    row[3][q] = t.x;
    row[4][q] = t.y;
    row[5][q] = t.z;
  }
};
}  // namespace detail

// A law whose history, seen from the other body, is the negation of its own (Law::history_mirrors).
template <class Law>
concept MirroredHistory = Law::history > 0 && requires {
  requires Law::history_mirrors;
};

// The forces of a queue of pairs (PairQueue), in one loop the compiler vectorises: a law written with
// selects runs on SIMD lanes with the same bits, as lanes do the same IEEE operations in the same
// order. With on_j, j's contribution is formed from the same evaluation: seen from j, the contact's
// kinematics are the exact negation of those seen from i (IEEE subtraction, products and the
// minimum-image wrap are antisymmetric), so a law written with vector operations returns the same F_n
// and the negated tangential force and torque there; a law whose history mirrors holds the negated
// history there too, so the same holds for it step after step (values equal; a zero's sign aside).
template <class Law, class Real>
void evaluate_pairs(const Law &shared_law, const Particles<Real> &shared_p, const PairQueue<Real> &q) {
  const Law law = shared_law;           // copies the loop's stores cannot alias: their
  const Particles<Real> p = shared_p;   // constants and pointers stay in registers
  const std::uint32_t n = q.n;
  const std::uint32_t *qi = q.i, *qj = q.j;
  const Real *dx = q.dx, *dy = q.dy, *dz = q.dz;
  const detail::QueueRows<Real> on_i(q.on_i, q.stride), on_j(q.on_j, q.stride);
  if constexpr (Law::history == 0 || MirroredHistory<Law>) {
    if (q.on_j) {
      // ivdep, not omp simd: GCC 12 does not vectorise this loop with the lanes' private copies omp simd makes
#pragma GCC ivdep
      for (std::uint32_t k = 0; k < n; ++k) {
        const Vec3<Real> d{dx[k], dy[k], dz[k]};
        const ContactState<Real> c = pair_contact_state(p, qi[k], qj[k], d, dot(d, d));
        Real *h = Law::history ? q.hist + std::size_t(k) * Law::history : nullptr;  // the queue's copy
        const ContactForce<Real> f = law(c, h);
        const ContactForce<Real> mirrored{f.normal, -f.tangent, -f.torque};  // the law's answer seen from j
        Vec3<Real> a{0, 0, 0}, ta{0, 0, 0}, b{0, 0, 0}, tb{0, 0, 0};
        accumulate(f, c.normal, p.r[qi[k]], a, ta);
        accumulate(mirrored, -c.normal, p.r[qj[k]], b, tb);
        on_i.put(k, a, ta);
        on_j.put(k, b, tb);
      }
      return;
    }
  }
#pragma GCC ivdep
  for (std::uint32_t k = 0; k < n; ++k) {
    const Vec3<Real> d{dx[k], dy[k], dz[k]};
    const ContactState<Real> c = pair_contact_state(p, qi[k], qj[k], d, dot(d, d));
    Real *h = Law::history ? q.hist + std::size_t(q.entry[k]) * Law::history : nullptr;
    Vec3<Real> a{0, 0, 0}, ta{0, 0, 0};
    accumulate(law(c, h), c.normal, p.r[qi[k]], a, ta);
    on_i.put(k, a, ta);
  }
}

// The forces of a queue of particles on one wall (WallQueue): the same bits as wall_force_on.
template <class Law, class Real>
void evaluate_walls(const Law &shared_law, const Particles<Real> &shared_p, const WallContacts<Real> &shared_w,
                    const WallQueue<Real> &q) {
  const Law law = shared_law;
  const Particles<Real> p = shared_p;
  const WallContacts<Real> w = shared_w;
  const std::uint32_t n = q.n;
  const std::uint32_t *qi = q.i;
  const detail::QueueRows<Real> out(q.out, q.stride);
#pragma GCC ivdep
  for (std::uint32_t k = 0; k < n; ++k) {
    const std::uint32_t i = qi[k];
    const ContactState<Real> c = wall_contact_state(p, w, i);
    Real *h = Law::history ? w.hist + std::size_t(i) * Law::history : nullptr;
    Vec3<Real> force{0, 0, 0}, torque{0, 0, 0};
    accumulate(law(c, h), c.normal, p.r[i], force, torque);
    out.put(k, force, torque);
  }
}

// A law with the cohesion part (contact_parts.hpp) has a member `cohesion`, and one with the rolling
// part a member `rolling`; it writes its force as
//   template <bool Cohesive, RollingForm Rolls, class Real>
//   SM_HD ContactForce<Real> force(const ContactState<Real> &, Real *hist) const;
// (without the rolling part: force<Cohesive>) with each part under `if constexpr`. Its loops are compiled
// for each choice, through LoopForm, and the choice is made once per batch (in_loop_form): a scene without
// cohesion or rolling friction runs the law's code without them, the same instructions and bits as a law
// that never had them (a loop whose lanes all compute a part and drop it still pays for its square roots
// and divides). The rolling spring adds its history after the law's: history_of(law) per instance.
// A law may compile a run-time choice of its own into its loops the same way (its slider kind, say):
// it declares `static constexpr int own_forms` and `int own_form() const` (0 .. own_forms - 1), and its
// force takes the form as a third parameter, force<Cohesive, Rolls, Own>, where any_own_form means
// "read the choice per contact" (the law's plain call, and the CUDA kernels).
template <class Law>
concept HasCohesion = requires(const Law &law) {
  { law.cohesion.on } -> std::convertible_to<bool>;
};
template <class Law>
concept HasRolling = requires(const Law &law) {
  { law.rolling.spring } -> std::convertible_to<bool>;
};

// History values the rolling spring (Rolling in contact_parts.hpp) keeps after its law's own.
inline constexpr int rolling_spring_history = 3;

// The rolling part a loop is compiled with: none (no rolling friction), the constant torque, or the
// spring (its history after the law's).
enum class RollingForm { none, constant, spring };
template <RollingForm Rolls>
inline constexpr int rolling_history = Rolls == RollingForm::spring ? rolling_spring_history : 0;

inline constexpr int any_own_form = -1;
template <class Law>
concept HasOwnForms = requires(const Law &law) {
  { Law::own_forms } -> std::convertible_to<int>;
  { law.own_form() } -> std::convertible_to<int>;
};

template <class Law, bool Cohesive, RollingForm Rolls, int Own = any_own_form> struct LoopForm {
  static constexpr RollingForm rolling = Rolls;
  static constexpr int own_form = Own;
  static constexpr int history = Law::history + rolling_history<Rolls>;
  // the rolling spring's history mirrors: the form's does when the law's own does, or when it has none
  static constexpr bool history_mirrors = Law::history == 0 || MirroredHistory<Law>;
  Law law;
  SM_HD double range() const requires Cohesive { return law.cohesion.range; }
  template <class Real> SM_HD ContactForce<Real> operator()(const ContactState<Real> &c, Real *hist) const {
    if constexpr (HasOwnForms<Law>) return law.template force<Cohesive, Rolls, Own>(c, hist);
    else if constexpr (HasRolling<Law>) return law.template force<Cohesive, Rolls>(c, hist);
    else return law.template force<Cohesive>(c, hist);
  }
};

// History values per contact of this instance of the law.
template <class Law> int history_of(const Law &law) {
  if constexpr (HasRolling<Law>) return Law::history + (law.rolling.spring ? rolling_spring_history : 0);
  else return Law::history;
}

namespace detail {
// Calls with.template operator()<form>() for the law's own form `form` of `Forms` (any_own_form when
// out of range).
template <int Forms, class With> decltype(auto) with_own_form(int form, With &&with) {
  if constexpr (Forms == 0) {
    return with.template operator()<any_own_form>();
  } else {
    if (form == Forms - 1) return with.template operator()<Forms - 1>();
    return with_own_form<Forms - 1>(form, with);
  }
}
}  // namespace detail

// The forms a loop is compiled for: every form (the queues of the CPU engine, where the time goes); the
// rolling spring's and the constant torque's without own forms (the whole-list loops, which only hosts
// before ABI 10.3 and the tests' reference loops call); the constant torque's alone, without own forms
// (the CUDA kernels, which keep the law's own history: the host steps a scene with a spring on the CPU).
// The fewer forms, the shorter a plugin's build; the forms left out read the choice per contact, with
// the same bits.
enum class LoopForms { queues, whole_list, kernels };

// Calls run(law as the loops take it): LoopForm<Law, cohesion on?, its rolling form, its own form> for a
// law with any of them, else the law.
template <LoopForms Forms = LoopForms::queues, class Law, class Run>
decltype(auto) in_loop_form(const Law &law, Run &&run) {
  if constexpr (HasCohesion<Law> || HasRolling<Law> || HasOwnForms<Law>) {
    bool cohesive = false;
    if constexpr (HasCohesion<Law>) cohesive = law.cohesion.on;
    auto with = [&]<RollingForm Rolls>() -> decltype(auto) {
      auto own = [&]<int Own>() -> decltype(auto) {
        if constexpr (HasCohesion<Law>)
          if (cohesive) return run(LoopForm<Law, true, Rolls, Own>{law});
        return run(LoopForm<Law, false, Rolls, Own>{law});
      };
      if constexpr (Forms == LoopForms::queues && HasOwnForms<Law>)
        return detail::with_own_form<Law::own_forms>(law.own_form(), own);
      else return own.template operator()<any_own_form>();
    };
    if constexpr (Forms != LoopForms::kernels && HasRolling<Law>)
      if (law.rolling.spring) return with.template operator()<RollingForm::spring>();
    if constexpr (Forms == LoopForms::queues && HasRolling<Law>)
      if (!(law.rolling.mu_r > 0)) return with.template operator()<RollingForm::none>();
    return with.template operator()<RollingForm::constant>();
  } else {
    return run(law);
  }
}

namespace detail {
template <class Law> struct ContactOps {
  static const Law &law(const void *s) { return *static_cast<const Law *>(s); }
  static double frequency(const void *s, double m, double r) { return law(s).natural_frequency(m, r); }
  static double zeta(const void *s, double m, double r) { return law(s).damping_ratio(m, r); }
  static int torque(const void *s) { return law(s).makes_torque() ? 1 : 0; }
  static double range(const void *s) {
    if constexpr (HasCohesion<Law>) return law(s).cohesion.range;
    else return 0;
  }
  // The whole-list loops of hosts before ABI 10.3 (on the caller's thread; they share no work).
  template <class Real> static void pairs(const void *s, const Particles<Real> *p, const PairList<Real> *l) {
    in_loop_form<LoopForms::whole_list>(law(s), [&](const auto &form) {
      for (std::uint32_t i = 0; i < p->n; ++i) pair_forces_on(form, *p, *l, i);
    });
  }
  template <class Real> static void walls(const void *s, const Particles<Real> *p, const WallContacts<Real> *w) {
    in_loop_form<LoopForms::whole_list>(law(s), [&](const auto &form) {
      for (std::uint32_t i = 0; i < w->n; ++i) wall_force_on(form, *p, *w, i);
    });
  }
  template <class Real> static void pair_queue(const void *s, const Particles<Real> *p, const PairQueue<Real> *q) {
    in_loop_form(law(s), [&](const auto &form) { with_simd([&] { evaluate_pairs(form, *p, *q); }); });
  }
  template <class Real>
  static void wall_queue(const void *s, const Particles<Real> *p, const WallContacts<Real> *w, const WallQueue<Real> *q) {
    in_loop_form(law(s), [&](const auto &form) { with_simd([&] { evaluate_walls(form, *p, *w, *q); }); });
  }
  static std::uint32_t history(const void *s) { return static_cast<std::uint32_t>(history_of(law(s))); }
  static int mirrors(const void *) { return Law::history == 0 || MirroredHistory<Law> ? 1 : 0; }
  static constexpr std::uint32_t most_history = Law::history + (HasRolling<Law> ? rolling_spring_history : 0);
#if SPREADMAP_TARGET_ABI_MINOR >= 4
  static constexpr sm_contact_ops_v1 table = {
      most_history,  &frequency, &zeta,   &torque,            &pairs<double>,     &pairs<float>,
      &walls<double>, &walls<float>, &range, &history, &pair_queue<double>, &pair_queue<float>,
      &wall_queue<double>, &wall_queue<float>, &mirrors};
#elif SPREADMAP_TARGET_ABI_MINOR >= 3
  static constexpr sm_contact_ops_v1 table = {
      most_history,  &frequency, &zeta,   &torque,            &pairs<double>,     &pairs<float>,
      &walls<double>, &walls<float>, &range, &history, &pair_queue<double>, &pair_queue<float>,
      &wall_queue<double>, &wall_queue<float>};
#elif SPREADMAP_TARGET_ABI_MINOR >= 1
  static constexpr sm_contact_ops_v1 table = {most_history,  &frequency,     &zeta,         &torque, &pairs<double>,
                                              &pairs<float>, &walls<double>, &walls<float>, &range,  &history};
#else
  static constexpr sm_contact_ops_v1 table = {Law::history,  &frequency,     &zeta,         &torque, &pairs<double>,
                                              &pairs<float>, &walls<double>, &walls<float>, &range};
#endif
};
}  // namespace detail

}  // namespace spreadmap

// Registers a contact law. The static_asserts read as sentences when a law breaks the rules.
#define SPREADMAP_CONTACT_PLUGIN(LAW, NAME, VERSION, SUMMARY)                                    \
  static_assert(std::is_trivially_copyable_v<LAW>,                                               \
                "a contact law must be trivially copyable: no virtuals, no std containers");     \
  static_assert(LAW::history >= 0, "a contact law must declare `static constexpr int history`"); \
  SPREADMAP_PLUGIN("contact", LAW, NAME, VERSION, SUMMARY, &::spreadmap::detail::ContactOps<LAW>::table)
