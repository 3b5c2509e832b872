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
// Touching pairs are queued, up to 64, and evaluated in one loop over the queue (kinematics, law and
// both contributions) that the compiler vectorises: a law without branches on the contact (selects
// instead) runs on SIMD lanes with the same bits, as lanes do the same IEEE operations in the same
// order. The contributions are then added one by one in queue order.
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
  std::uint32_t waiting_end = 0;  // no particle from here on waits (found by find_waiting_end)

  // True when particle i (of this range or above) has a lower neighbour in an earlier thread's range
  // (never in the first range).
  bool waits(const PairList<Real> &list, std::uint32_t i) const { return i < waiting_end && below_lo(list, i); }
  // Sets waiting_end past the last particle of the range that waits: they lie near its start (the
  // particles are sorted by cell), so that most tests of waits() end at the first comparison.
  void find_waiting_end(const PairList<Real> &list) {
    waiting_end = 0;
    if (lo > 0)
      for (std::uint32_t i = lo; i < hi; ++i) waiting_end = below_lo(list, i) ? i + 1 : waiting_end;
  }
  // Particle i's lowest neighbour lies below this range.
  bool below_lo(const PairList<Real> &list, std::uint32_t i) const {
    return list.start[i] < list.start[i + 1] && list.nbr[list.start[i]] < lo;
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

// A queue of touching pairs of one thread, evaluated when full or at the end.
template <class Law, class Real> struct PairBatch {
  static constexpr int capacity = 64;
  std::uint32_t i[capacity], j[capacity], k[capacity];
  Real dx[capacity], dy[capacity], dz[capacity];
  Real fi[6][capacity], fj[6][capacity];  // force and torque on i, then on j

  // Evaluates the first `size` queued pairs, in queue order, adding their contributions.
  void flush(int size, const Law &shared_law, const Particles<Real> &p, const PairList<Real> &list, PairSweep<Real> &sweep) {
    const Law law = shared_law;  // a copy the loop's stores cannot alias: its constants are invariant
    // ivdep, not omp simd: GCC 12 does not vectorise this loop with the lanes' private copies omp simd makes
#pragma GCC ivdep
    for (int q = 0; q < size; ++q) {
      const Vec3<Real> d{dx[q], dy[q], dz[q]};
      const ContactState<Real> c = pair_contact_state(p, i[q], j[q], d, dot(d, d));
      const ContactForce<Real> f = law(c, static_cast<Real *>(nullptr));
      const ContactForce<Real> mirrored{f.normal, -f.tangent, -f.torque};  // the law's answer seen from j
      Vec3<Real> a{0, 0, 0}, ta{0, 0, 0}, b{0, 0, 0}, tb{0, 0, 0};
      accumulate(f, c.normal, p.r[i[q]], a, ta);
      accumulate(mirrored, -c.normal, p.r[j[q]], b, tb);
      fi[0][q] = a.x; fi[1][q] = a.y; fi[2][q] = a.z; fi[3][q] = ta.x; fi[4][q] = ta.y; fi[5][q] = ta.z;
      fj[0][q] = b.x; fj[1][q] = b.y; fj[2][q] = b.z; fj[3][q] = tb.x; fj[4][q] = tb.y; fj[5][q] = tb.z;
    }
    for (int q = 0; q < size; ++q) {
      const std::uint32_t entry = k[q];
      sweep.add(list, i[q], [&] { return entry; }, {fi[0][q], fi[1][q], fi[2][q]}, {fi[3][q], fi[4][q], fi[5][q]});
      sweep.add(list, j[q], [&] { return list.mirror[entry]; }, {fj[0][q], fj[1][q], fj[2][q]}, {fj[3][q], fj[4][q], fj[5][q]});
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
// same bits as wrap() (d - L, d - (-L) = d + L, or d - 0 = d, for -0 too), the shift a select.
template <bool Periodic, class Real> Real wrap_axis(Real d, Real length) {
  if constexpr (Periodic) {
    const Real h = Real(0.5) * length;
    return d - (d > h ? length : (d < -h ? -length : Real(0)));
  } else {
    (void)length;
    return d;
  }
}

// One thread's sweep of pair_loop_once over its range, compiled once per combination of periodic
// axes so that the filter of the list has no branch on them.
template <bool PX, bool PY, bool PZ, class Law, class Real>
SM_CPU_CLONES void sweep_pairs(const Law &law, const Particles<Real> &p, const PairList<Real> &list,
                               PairSweep<Real> &shared_sweep) {
  PairSweep<Real> sweep = shared_sweep;  // a copy the stores into the list cannot alias: kept in registers
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
    std::uint32_t k = begin;
    if (list.upper) k = list.upper[i];
    else
      for (std::uint32_t q = begin; q < end; ++q) k += list.nbr[q] < i ? 1u : 0u;
    if (k == end) continue;
    // Slots to clear: none when neither i nor any of its upper neighbours waits (the usual case,
    // always in the first range); the loop without them is the hot one.
    const bool i_waits = sweep.waits(list, i);
    const bool clears = i_waits || list.nbr[end - 1] >= hi || i + 1 < sweep.waiting_end;
    auto queue = [&]<bool Clears>(std::uint32_t from, std::uint32_t to) {
      for (std::uint32_t q = from; q < to; ++q) {
        const std::uint32_t j = list.nbr[q];
        const Vec3<Real> d{wrap_axis<PX>(xi - p.x[j], lx), wrap_axis<PY>(yi - p.y[j], ly), wrap_axis<PZ>(zi - p.z[j], lz)};
        const Real reach = ri + p.r[j];
        if constexpr (Clears) {
          if (i_waits) list.slot[q] = 0;
          if (j >= hi || sweep.waits(list, j)) list.slot[list.mirror[q]] = 0;
        }
        batch.i[queued] = i; batch.j[queued] = j; batch.k[queued] = q;
        batch.dx[queued] = d.x; batch.dy[queued] = d.y; batch.dz[queued] = d.z;
        queued += dot(d, d) < reach * reach ? 1 : 0;  // kept only when touching, without a branch
      }
    };
    while (k < end) {
      // the queue takes as many of i's entries as it has room for; full, it is evaluated first
      if (queued == batch.capacity) {
        batch.flush(queued, law, p, list, sweep);
        queued = 0;
        finish_up_to(i);  // every pair of the particles before i is evaluated
      }
      const std::uint32_t stop = min(end, k + std::uint32_t(batch.capacity - queued));
      if (clears) queue.template operator()<true>(k, stop);
      else queue.template operator()<false>(k, stop);
      k = stop;
    }
  }
  batch.flush(queued, law, p, list, sweep);
  finish_up_to(hi);
  shared_sweep = sweep;
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
    sweep.find_waiting_end(list);
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
