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
// How the order is kept: each thread sweeps a range [lo, hi) of particles (cut by list entries, in
// shares tuned from the threads' last timings; which thread evaluates a pair does not change the
// result) in increasing order, through the flat sequence of their upper entries (j > i, see
// PairList). Particle j's list holds its lower neighbours first, by increasing index, then its upper
// ones; the sweep meets them in that very order (j's lower neighbours are rows before j; its upper
// entries are j's own row). So a contribution is added straight to the particle's running sum (in
// the scratch after the records), and the sum goes to the particle once the sweep has passed it. A
// particle with a lower neighbour below lo gets contributions from another thread: its contributions
// are kept as records instead, one per list entry (an entry that does not touch keeps its zero
// record), and it is summed in list order after a barrier, its records cleared again.
//
// Touching pairs (and pairs within a law's range across a gap) are queued and evaluated in one loop over the queue
// (kinematics, law and both contributions) that the compiler vectorises: a law without branches on the contact (selects
// instead) runs on SIMD lanes with the same bits, as lanes do the same IEEE operations in the same
// order. The contributions are then added one by one in queue order. The filter that fills the queue
// runs over the flat pair sequence in fixed chunks, with no exit per particle to mispredict.
#pragma once
#include <spreadmap/contact.hpp>
#include <spreadmap/simd.hpp>
#include <spreadmap/team.hpp>

#include <algorithm>
#include <chrono>

namespace spreadmap {

namespace detail {
// The particles [lo, hi) of thread t of nt, cut where the list entries are shared as `balance` says
// (equally without one, or when it is for another number of threads).
inline void entry_balanced_range(const std::uint32_t *start, std::uint32_t n, int t, int nt, const PairBalance *balance,
                                 std::uint32_t &lo, std::uint32_t &hi) {
  const std::uint64_t entries = start[n];
  const bool tuned = balance && balance->threads == nt;
  auto cut = [&](int k) -> std::uint32_t {
    if (k >= nt) return n;
    const std::uint64_t target =
        tuned ? std::uint64_t(double(entries) * balance->cut[k]) : entries * std::uint64_t(k) / std::uint64_t(nt);
    return static_cast<std::uint32_t>(std::lower_bound(start, start + n, target) - start);
  };
  lo = cut(t);
  hi = cut(t + 1);
}

// After a sweep of nt threads: moves the cuts half way towards shares in proportion to each thread's
// speed (its share over its time), so that the threads finish together. Half way: one slow sweep (a
// thread preempted) moves them only so far. No share falls below a quarter of an equal one.
inline void retune(PairBalance &b, int nt) {
  if (nt < 2 || nt > PairBalance::max_threads) return;
  if (b.threads != nt) {  // the sweep just timed had equal shares
    b.threads = nt;
    for (int k = 0; k <= nt; ++k) b.cut[k] = double(k) / nt;
  }
  double speed[PairBalance::max_threads], total = 0;
  for (int t = 0; t < nt; ++t) {
    if (!(b.seconds[t] > 0)) return;
    speed[t] = (b.cut[t + 1] - b.cut[t]) / b.seconds[t];
    total += speed[t];
  }
  if (!(total > 0)) return;
  double share[PairBalance::max_threads], sum = 0;
  for (int t = 0; t < nt; ++t) sum += share[t] = std::max(speed[t] / total, 0.25 / nt);
  double end = 0;
  for (int t = 0; t + 1 < nt; ++t) {
    end += share[t] / sum;
    b.cut[t + 1] = 0.5 * (b.cut[t + 1] + end);
  }
  b.cut[0] = 0;
  b.cut[nt] = 1;
}

// Particle i's lowest neighbour lies below `lo` (the start of a thread's range): i waits for records.
template <class Real> bool neighbour_below(const PairList<Real> &list, std::uint32_t i, std::uint32_t lo) {
  return list.start[i] < list.start[i + 1] && list.nbr[list.start[i]] < lo;
}

// One thread's share of the loop: its range, and where its running sums live.
template <class Real> struct PairSweep {
  std::uint32_t lo, hi;
  Real *sums;                     // 6 per particle, indexed by particle
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
  bool below_lo(const PairList<Real> &list, std::uint32_t i) const { return neighbour_below(list, i, lo); }
  // Adds contribution (f, t) of entry k (k_of() gives it; only records need it) to particle i: to its
  // running sum when the sweep keeps its order, else as the entry's record.
  template <class EntryOf>
  void add(const PairList<Real> &list, std::uint32_t i, EntryOf k_of, const Vec3<Real> &f, const Vec3<Real> &t) {
    Real *s = i < hi && !waits(list, i) ? sums + std::size_t(i) * 6 : list.scratch + std::size_t(k_of()) * 6;
    s[0] += f.x;
    s[1] += f.y;
    s[2] += f.z;
    s[3] += t.x;
    s[4] += t.y;
    s[5] += t.z;  // a record: 0 + c = c
  }
};

// The entry (i, j) of particle i's list, j > i (upper entries are listed by index).
template <class Real> std::uint32_t upper_entry(const PairList<Real> &list, std::uint32_t i, std::uint32_t j) {
  return static_cast<std::uint32_t>(std::lower_bound(list.nbr + list.upper[i], list.nbr + list.start[i + 1], j) -
                                    list.nbr);
}

// A queue of touching pairs of one thread, evaluated when full or at the end.
template <class Law, class Real> struct PairBatch {
  static constexpr int capacity = 64;
  static constexpr int chunk = 16;  // pairs filtered between checks of the room left
  std::uint32_t i[capacity + chunk], j[capacity + chunk];
  Real dx[capacity + chunk], dy[capacity + chunk], dz[capacity + chunk];
  Real fi[6][capacity], fj[6][capacity];  // force and torque on i, then on j

  // Evaluates the first `size` queued pairs, in queue order, adding their contributions.
  void flush(int size, const Law &shared_law, const Particles<Real> &p, const PairList<Real> &list,
             PairSweep<Real> &sweep) {
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
      fi[0][q] = a.x;
      fi[1][q] = a.y;
      fi[2][q] = a.z;
      fi[3][q] = ta.x;
      fi[4][q] = ta.y;
      fi[5][q] = ta.z;
      fj[0][q] = b.x;
      fj[1][q] = b.y;
      fj[2][q] = b.z;
      fj[3][q] = tb.x;
      fj[4][q] = tb.y;
      fj[5][q] = tb.z;
    }
    for (int q = 0; q < size; ++q) {
      const std::uint32_t pi = i[q], pj = j[q];
      // records only: the entry, looked up (rare: particles at the border of a thread's range)
      auto entry = [&] { return upper_entry(list, pi, pj); };
      sweep.add(list, pi, entry, {fi[0][q], fi[1][q], fi[2][q]}, {fi[3][q], fi[4][q], fi[5][q]});
      sweep.add(list, pj, [&] { return list.mirror[entry()]; }, {fj[0][q], fj[1][q], fj[2][q]},
                {fj[3][q], fj[4][q], fj[5][q]});
    }
  }
};

// Adds particle i's records, in list order, to its accumulators, and clears them for the next call.
template <class Real> void add_records(const Particles<Real> &p, const PairList<Real> &list, std::uint32_t i) {
  Real s[6] = {0, 0, 0, 0, 0, 0};
  for (std::uint32_t k = list.start[i]; k < list.start[i + 1]; ++k) {
    Real *r = list.scratch + std::size_t(k) * 6;
    for (int c = 0; c < 6; ++c) {
      s[c] += r[c];
      r[c] = 0;
    }
  }
  p.fx[i] += s[0];
  p.fy[i] += s[1];
  p.fz[i] += s[2];
  p.tx[i] += s[3];
  p.ty[i] += s[4];
  p.tz[i] += s[5];
}

// The particles of one thread's range that may wait for records: [lo, end).
struct WaitingSpan {
  std::uint32_t lo, end;
};

// After the barrier: the records of the particles that wait, summed by the whole team. The waiting
// particles all lie in the ranges after the first (near their starts), so that left to their own
// threads the last threads would sum while the first wait; here each thread takes an equal part of
// the spans laid end to end. Which thread sums a particle changes no bit: its records are added in
// list order either way.
template <class Real>
void add_waiting_records(const Particles<Real> &p, const PairList<Real> &list, const WaitingSpan *spans,
                         TeamSlot team) {
  std::uint64_t total = 0;
  for (int u = 0; u < team.threads; ++u) total += spans[u].end - spans[u].lo;
  const TeamRange mine = team_share(total, team);
  std::uint64_t at = 0;  // position of span u's first particle in the spans laid end to end
  for (int u = 0; u < team.threads && at < mine.hi; ++u) {
    const WaitingSpan s = spans[u];
    const std::uint64_t length = s.end - s.lo;
    const std::uint64_t from = std::max<std::uint64_t>(at, mine.lo), to = std::min<std::uint64_t>(at + length, mine.hi);
    for (std::uint64_t q = from; q < to; ++q) {
      const auto i = static_cast<std::uint32_t>(s.lo + (q - at));
      if (neighbour_below(list, i, s.lo)) add_records(p, list, i);
    }
    at += length;
  }
}

// Minimum image along one axis, the periodicity fixed at compile time and no branch taken: the
// same bits as wrap() (d - L, d - (-L) = d + L, or d - 0 - 0 = d, for -0 too), the shifts selects.
template <bool Periodic, class Real> Real wrap_axis(Real d, Real length) {
  if constexpr (Periodic) {
    const Real h = Real(0.5) * length;
    return (d - (d > h ? length : Real(0))) - (d < -h ? -length : Real(0));
  } else {
    (void)length;
    return d;
  }
}

// One thread's sweep of pair_loop_once over its range, compiled once per combination of periodic
// axes so that the filter has no branch on them.
template <bool PX, bool PY, bool PZ, class Law, class Real>
void sweep_pairs(const Law &law, const Particles<Real> &p, const PairList<Real> &list, PairSweep<Real> &shared_sweep) {
  PairSweep<Real> sweep = shared_sweep;  // a copy the stores into the queue cannot alias: kept in registers
  const Real lx = p.box_hi[0] - p.box_lo[0], ly = p.box_hi[1] - p.box_lo[1], lz = p.box_hi[2] - p.box_lo[2];
  const Real *x = p.x, *y = p.y, *z = p.z, *r = p.r;
  const std::uint32_t *pair_i = list.pair_i, *pair_j = list.pair_j;
  std::uint32_t done = sweep.lo;  // the particles below this one got their sums (or wait for the barrier)
  auto finish_up_to = [&](std::uint32_t end) {
    for (; done < end; ++done) {
      if (sweep.waits(list, done)) continue;
      Real *s = sweep.sums + std::size_t(done) * 6;
      p.fx[done] += s[0];
      p.fy[done] += s[1];
      p.fz[done] += s[2];
      p.tx[done] += s[3];
      p.ty[done] += s[4];
      p.tz[done] += s[5];
      for (int c = 0; c < 6; ++c) s[c] = 0;  // left as found: the next call starts from zero sums
    }
  };
  using Batch = PairBatch<Law, Real>;
  Batch batch;
  int queued = 0;
  const std::uint32_t end = list.first_pair[sweep.hi];
  for (std::uint32_t u = list.first_pair[sweep.lo]; u < end;) {
    // a chunk of pairs, each written to the queue and kept (counted) only when touching: no branch
    const std::uint32_t stop = min(end, u + std::uint32_t(Batch::chunk));
    for (; u < stop; ++u) {
      const std::uint32_t i = pair_i[u], j = pair_j[u];
      const Real ddx = wrap_axis<PX>(x[i] - x[j], lx), ddy = wrap_axis<PY>(y[i] - y[j], ly),
                 ddz = wrap_axis<PZ>(z[i] - z[j], lz);
      const Real reach = interaction_reach(law, r[i], r[j]);
      batch.i[queued] = i;
      batch.j[queued] = j;
      batch.dx[queued] = ddx;
      batch.dy[queued] = ddy;
      batch.dz[queued] = ddz;
      queued += ddx * ddx + ddy * ddy + ddz * ddz < reach * reach ? 1 : 0;
    }
    if (queued > Batch::capacity - Batch::chunk) {
      batch.flush(queued, law, p, list, sweep);
      queued = 0;
      finish_up_to(u < end ? pair_i[u] : sweep.hi);  // every pair of the particles before is evaluated
    }
  }
  batch.flush(queued, law, p, list, sweep);
  finish_up_to(sweep.hi);
  shared_sweep = sweep;
}
}  // namespace detail

template <class Law, class Real>
void pair_loop_once(const Law &law, const Particles<Real> &p, const PairList<Real> &list) {
  static_assert(Law::history == 0, "a law with history is evaluated for every entry");
  const bool px = p.periodic[0] != 0, py = p.periodic[1] != 0, pz = p.periodic[2] != 0;
  int threads = 1;
  detail::WaitingSpan waiting[PairBalance::max_threads];
  run_team(p.team, [&](TeamSlot team) {
    const int t = team.thread, nt = team.threads;
    const auto began = std::chrono::steady_clock::now();
    detail::PairSweep<Real> sweep;
    detail::entry_balanced_range(list.start, p.n, t, nt, list.balance, sweep.lo, sweep.hi);
    sweep.sums = list.scratch + std::size_t(list.start[p.n]) * 6;  // after the records; zero on entry and exit
    sweep.find_waiting_end(list);
    auto sweep_with = [&]<bool PX, bool PY, bool PZ>() {
      with_simd([&] { detail::sweep_pairs<PX, PY, PZ>(law, p, list, sweep); });
    };
    if (px) {
      if (py)
        pz ? sweep_with.template operator()<true, true, true>() : sweep_with.template operator()<true, true, false>();
      else
        pz ? sweep_with.template operator()<true, false, true>() : sweep_with.template operator()<true, false, false>();
    } else {
      if (py)
        pz ? sweep_with.template operator()<false, true, true>() : sweep_with.template operator()<false, true, false>();
      else
        pz ? sweep_with.template operator()<false, false, true>()
           : sweep_with.template operator()<false, false, false>();
    }
    const auto swept = std::chrono::steady_clock::now();
    const bool shared = nt <= PairBalance::max_threads;
    if (shared) waiting[t] = {sweep.lo, std::max(sweep.lo, sweep.waiting_end)};
    team_barrier(p.team);
    const auto summing = std::chrono::steady_clock::now();
    if (shared) {
      detail::add_waiting_records(p, list, waiting, team);
    } else {
      for (std::uint32_t i = sweep.lo; i < sweep.hi; ++i)
        if (sweep.waits(list, i)) detail::add_records(p, list, i);
    }
    // the thread's work, without its wait at the barrier
    if (list.balance && t < PairBalance::max_threads)
      list.balance->seconds[t] =
          std::chrono::duration<double>(swept - began + (std::chrono::steady_clock::now() - summing)).count();
    if (t == 0) threads = nt;
  });
  if (list.balance) detail::retune(*list.balance, threads);  // every thread is done with the cuts
}

}  // namespace spreadmap
