// The CPU pair loop that evaluates each touching pair once (laws without history, when the engine
// gives PairList::mirror and its scratch). Included at the end of contact.hpp; not a header of its own.
//
// Why it gives the same bits as evaluating every entry (pair_forces_on): seen from j, the contact's
// kinematics are the exact negation of those seen from i (IEEE subtraction, products and the
// minimum-image wrap are antisymmetric; sums of the same two terms commute), so a law written with
// vector operations returns the same F_n and the negated tangential force and torque. The pair is
// therefore evaluated by its lower-index particle i, j's contribution is formed from the same
// result with j's normal and radius, and each particle still adds its contributions in list order.
// Results do not depend on the number of threads.
//
// How the order is kept: each thread sweeps a range [lo, hi) of particles (balanced by list
// entries) in increasing order, testing the upper entries (j > i) of each. Particle j's list holds
// its lower neighbours first, by increasing index, then its upper ones; the sweep meets them in that
// very order (j's lower neighbours are rows before j; its upper entries are j's own row). So a
// contribution is added straight to the particle's running sum (in the scratch after the records),
// and the sum goes to the particle once the sweep has passed it. A particle with a lower neighbour
// below lo gets contributions from another thread: its contributions are kept as records instead
// (slot[k] names entry k's record, 0 an all-zero one), and it is summed in list order after a
// barrier. Thread t's records start at 1 + 2 * (entries before its range), so runs never overlap.
//
// Touching pairs are queued and evaluated in short loops over up to 64 contacts (kinematics, law,
// contributions), so that the core overlaps many contacts' sqrt/div chains.
#pragma once
#include <spreadmap/contact.hpp>
#include <spreadmap/team.hpp>

#include <algorithm>
#ifdef _OPENMP
#include <omp.h>
#endif

namespace spreadmap {

namespace detail {
// The particles [lo, hi) of thread t of nt, cut where the list entries are shared equally.
inline void entry_balanced_range(const std::uint32_t *start, std::uint32_t n, int t, int nt, std::uint32_t &lo,
                                 std::uint32_t &hi) {
  const std::uint64_t entries = start[n];
  auto cut = [&](int k) -> std::uint32_t {
    if (k >= nt) return n;
    const std::uint64_t target = entries * std::uint64_t(k) / std::uint64_t(nt);
    return static_cast<std::uint32_t>(std::lower_bound(start, start + n, target) - start);
  };
  lo = cut(t);
  hi = cut(t + 1);
}

// One thread's share of the loop: its range, where its running sums and records live.
template <class Real> struct PairSweep {
  std::uint32_t lo, hi;
  Real *sums;       // 6 per particle, indexed by particle
  std::size_t next; // next free record

  // True when particle i (of this range) has a lower neighbour in another thread's range (never in
  // the first range).
  bool waits(const PairList<Real> &list, std::uint32_t i) const {
    return lo > 0 && list.start[i] < list.start[i + 1] && list.nbr[list.start[i]] < lo;
  }
  // Adds contribution (f, t) of entry k (k_of() gives it; only records need it) to particle i: to its
  // running sum when the sweep keeps its order, else as the entry's record.
  template <class EntryOf>
  void add(const PairList<Real> &list, std::uint32_t i, EntryOf k_of, const Vec3<Real> &f, const Vec3<Real> &t) {
    Real *s;
    if (i < hi && !waits(list, i)) {
      s = sums + std::size_t(i) * 6;
      s[0] += f.x; s[1] += f.y; s[2] += f.z; s[3] += t.x; s[4] += t.y; s[5] += t.z;
      return;
    }
    s = list.scratch + next * 6;
    s[0] = f.x; s[1] = f.y; s[2] = f.z; s[3] = t.x; s[4] = t.y; s[5] = t.z;
    list.slot[k_of()] = static_cast<std::uint32_t>(next++);
  }
};

// A queue of touching pairs of one thread, evaluated in stages when full or at the end.
template <class Law, class Real> struct PairBatch {
  static constexpr int capacity = 64;
  std::uint32_t i[capacity], k[capacity];
  Vec3<Real> d[capacity];
  ContactState<Real> state[capacity];
  ContactForce<Real> force[capacity];

  // Evaluates the first `size` queued pairs, in queue order, adding their contributions.
  void flush(int size, const Law &law, const Particles<Real> &p, const PairList<Real> &list, PairSweep<Real> &sweep) {
    for (int q = 0; q < size; ++q) state[q] = pair_contact_state(p, i[q], list.nbr[k[q]], d[q], dot(d[q], d[q]));
    for (int q = 0; q < size; ++q) force[q] = law(state[q], static_cast<Real *>(nullptr));
    for (int q = 0; q < size; ++q) {
      const ContactState<Real> &c = state[q];
      const ContactForce<Real> &f = force[q];
      const ContactForce<Real> mirrored{f.normal, -f.tangent, -f.torque};  // the law's answer seen from j
      const std::uint32_t j = list.nbr[k[q]];
      Vec3<Real> fi{0, 0, 0}, ti{0, 0, 0}, fj{0, 0, 0}, tj{0, 0, 0};
      accumulate(f, c.normal, p.r[i[q]], fi, ti);
      accumulate(mirrored, -c.normal, p.r[j], fj, tj);
      const std::uint32_t entry = k[q];
      sweep.add(list, i[q], [&] { return entry; }, fi, ti);
      sweep.add(list, j, [&] { return list.mirror[entry]; }, fj, tj);
    }
  }
};

// Adds particle i's records, in list order, to its accumulators.
template <class Real> void add_records(const Particles<Real> &p, const PairList<Real> &list, std::uint32_t i) {
  Real s[6] = {0, 0, 0, 0, 0, 0};
  for (std::uint32_t k = list.start[i]; k < list.start[i + 1]; ++k) {
    const Real *r = list.scratch + std::size_t(list.slot[k]) * 6;
    for (int c = 0; c < 6; ++c) s[c] += r[c];
  }
  p.fx[i] += s[0]; p.fy[i] += s[1]; p.fz[i] += s[2];
  p.tx[i] += s[3]; p.ty[i] += s[4]; p.tz[i] += s[5];
}

// Minimum image along one axis, the periodicity fixed at compile time and no branch taken: the
// same operations, hence the same bits, as wrap().
template <bool Periodic, class Real> Real wrap_axis(Real d, Real length) {
  if constexpr (Periodic) {
    const Real h = Real(0.5) * length;
    return d > h ? d - length : (d < -h ? d + length : d);
  } else {
    (void)length;
    return d;
  }
}

// One thread's sweep of pair_loop_once over its range, compiled once per combination of periodic
// axes so that the filter of the list has no branch on them.
template <bool PX, bool PY, bool PZ, class Law, class Real>
SM_CPU_CLONES void sweep_pairs(const Law &law, const Particles<Real> &p, const PairList<Real> &list, PairSweep<Real> &sweep) {
  const Real lx = p.box_hi[0] - p.box_lo[0], ly = p.box_hi[1] - p.box_lo[1], lz = p.box_hi[2] - p.box_lo[2];
  const std::uint32_t lo = sweep.lo, hi = sweep.hi;
  std::uint32_t done = lo;  // the particles below this one got their sums (or wait for the barrier)
  auto finish_up_to = [&](std::uint32_t end) {
    for (; done < end; ++done) {
      if (sweep.waits(list, done)) continue;
      Real *s = sweep.sums + std::size_t(done) * 6;
      p.fx[done] += s[0]; p.fy[done] += s[1]; p.fz[done] += s[2];
      p.tx[done] += s[3]; p.ty[done] += s[4]; p.tz[done] += s[5];
      for (int c = 0; c < 6; ++c) s[c] = 0;  // left as found: the next call starts from zero sums
    }
  };
  PairBatch<Law, Real> batch;
  int queued = 0;
  // Slots are read only for particles that wait (those of later ranges too, and none of the first
  // range); their touching entries are set again when evaluated, the others must read 0.
  for (std::uint32_t i = lo; i < hi; ++i) {
    const Real xi = p.x[i], yi = p.y[i], zi = p.z[i], ri = p.r[i];
    const std::uint32_t begin = list.start[i], end = list.start[i + 1];
    // neighbours are listed by index: the upper ones follow the lower ones
    std::uint32_t first = begin;
    if (list.upper) first = list.upper[i];
    else
      for (std::uint32_t k = begin; k < end; ++k) first += list.nbr[k] < i ? 1u : 0u;
    const bool i_waits = sweep.waits(list, i);
    for (std::uint32_t k = first; k < end; ++k) {
      const std::uint32_t j = list.nbr[k];
      const Vec3<Real> d{wrap_axis<PX>(xi - p.x[j], lx), wrap_axis<PY>(yi - p.y[j], ly), wrap_axis<PZ>(zi - p.z[j], lz)};
      const Real reach = ri + p.r[j];
      if (i_waits) list.slot[k] = 0;
      if (j >= hi || sweep.waits(list, j)) list.slot[list.mirror[k]] = 0;
      batch.i[queued] = i; batch.k[queued] = k; batch.d[queued] = d;
      queued += dot(d, d) < reach * reach ? 1 : 0;  // kept only when touching, without a branch
      if (queued == batch.capacity) {
        batch.flush(queued, law, p, list, sweep);
        queued = 0;
        finish_up_to(i);  // every pair of the particles before i is evaluated
      }
    }
  }
  batch.flush(queued, law, p, list, sweep);
  finish_up_to(hi);
}
}  // namespace detail

template <class Law, class Real>
void pair_loop_once(const Law &law, const Particles<Real> &p, const PairList<Real> &list) {
  static_assert(Law::history == 0, "a law with history is evaluated for every entry");
  const std::size_t records = 2 * std::size_t(list.start[p.n]) + 1;
  const bool px = p.periodic[0] != 0, py = p.periodic[1] != 0, pz = p.periodic[2] != 0;
#pragma omp parallel
  {
    const auto [t, nt] = team_slot();
    detail::PairSweep<Real> sweep;
    detail::entry_balanced_range(list.start, p.n, t, nt, sweep.lo, sweep.hi);
    sweep.sums = list.scratch + records * 6;  // zero on entry (the list's contract), zero again on exit
    sweep.next = 1 + 2 * std::size_t(list.start[sweep.lo]);
    auto sweep_with = [&]<bool PX, bool PY, bool PZ>() { detail::sweep_pairs<PX, PY, PZ>(law, p, list, sweep); };
    if (px) {
      if (py) pz ? sweep_with.template operator()<true, true, true>() : sweep_with.template operator()<true, true, false>();
      else pz ? sweep_with.template operator()<true, false, true>() : sweep_with.template operator()<true, false, false>();
    } else {
      if (py) pz ? sweep_with.template operator()<false, true, true>() : sweep_with.template operator()<false, true, false>();
      else pz ? sweep_with.template operator()<false, false, true>() : sweep_with.template operator()<false, false, false>();
    }
#pragma omp barrier
    for (std::uint32_t i = sweep.lo; i < sweep.hi; ++i)
      if (sweep.waits(list, i)) detail::add_records(p, list, i);
  }
}

}  // namespace spreadmap
