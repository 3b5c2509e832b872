// The CPU engine's pair loops: they walk the neighbour list, queue the pairs within the law's reach and
// hand the law each queue (PairQueue, one call through the plugin's table per queue), then add the
// contributions in list order. How the list is walked and shared between threads lives here, not in
// any plugin: tuning it changes no struct of the plugin ABI.
//
// A law without history, given the list's mirror, has each touching pair evaluated once:
// the pair is evaluated by its lower-index particle i, and j's contribution comes from the same
// evaluation (evaluate_pairs in spreadmap/contact.hpp says why the bits are those of evaluating both
// entries); each particle still adds its contributions in list order. Results do not depend on the
// number of threads.
//
// How the order is kept: each thread sweeps a range [lo, hi) of particles (cut by list entries, in
// shares tuned from the threads' last timings; which thread evaluates a pair does not change the
// result) in increasing order, through the flat sequence of their upper entries (j > i). Particle j's
// list holds its lower neighbours first, by increasing index, then its upper ones; the sweep meets them
// in that very order (j's lower neighbours are rows before j; its upper entries are j's own row). So a
// contribution is added straight to the particle's running sum (in the scratch after the records), and
// the sum goes to the particle once the sweep has passed it. A particle with a lower neighbour below lo
// gets contributions from another thread: its contributions are kept as records instead, one per list
// entry (an entry that does not touch keeps its zero record), and it is summed in list order after a
// barrier, its records cleared again.
//
// A law whose history mirrors (law_pairs_once: its values seen from j are the negation of those seen
// from i) has each touching pair evaluated once too, with the history of the pair's entry (i, j); the
// loop then writes the negation to the mirror entry (j, i), and clears both entries of a pair out of
// reach that holds any value. The list's history is then that of evaluating every entry (equal values;
// a zero's sign may differ), and so are the forces, bit for bit.
//
// Any other law with history (or a list without mirrors) has every entry evaluated with its own
// history: each thread sweeps its particles' full lists, clears the history of entries out of reach,
// and queues the others.
#pragma once
#include <engine/history_values.hpp>
#include <engine/minimum_image.hpp>
#include <engine/pair_filter.hpp>
#include <engine/team.hpp>
#include <engine/thread_team.hpp>
#include <spreadmap/batch.hpp>
#include <spreadmap/contact.hpp>
#include <spreadmap/simd.hpp>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <type_traits>

namespace spreadmap::engine {

// How the threads of the pair loop share its list entries, tuned by the loop from how long each
// thread took: the split decides which thread evaluates a pair, never the result. Zero at first.
struct PairBalance {
  static constexpr int max_threads = 64;
  std::int32_t threads;         // cut is for this many threads (otherwise equal shares)
  double cut[max_threads + 1];  // thread t takes the entries from cut[t] to cut[t + 1] x all
  double seconds[max_threads];  // each thread's last sweep
};

// The list as the pair loops walk it: the plugin ABI's list (start, nbr, hist) and, for the loop that
// evaluates each pair once (law_pairs_once), each entry's mirror (the entry (j, i) of (i, j)), each particle's first
// upper entry (j > i), the upper entries of all particles as one flat sequence (pair u is (pair_i[u], pair_j[u]), the
// list's entry pair_entry[u]; particle i's are [first_pair[i], first_pair[i + 1])), and the scratch: a record of 6
// values per entry, then 6 running sums per particle, all zero on entry to the loop and on exit; room for each
// particle's position and radius packed side by side (engine/pair_filter.hpp, 32 bytes aligned); and for a law with
// history, in_reach[u]: 1 when pair u was within the law's reach at its last filter (and, after a build, for every
// pair: any may hold carried history), else 0: a pair out of reach that was out of reach before holds no history
// (the loop cleared it then), so only the others are read. Null where absent.
template <class Real> struct ListView {
  const std::uint32_t *start = nullptr, *nbr = nullptr;
  Real *hist = nullptr;
  const std::uint32_t *mirror = nullptr;
  Real *scratch = nullptr;
  const std::uint32_t *upper = nullptr;
  const std::uint32_t *pair_i = nullptr, *pair_j = nullptr, *first_pair = nullptr, *pair_entry = nullptr;
  PairBalance *balance = nullptr;  // null: equal shares of the entries
  Real *packed = nullptr;
  std::uint8_t *in_reach = nullptr;

  bool once() const { return mirror && scratch && pair_i; }
  PairList<Real> whole() const { return {start, nbr, hist}; }
};

// What a loop hands its queues to: the law's queue function and instance.
template <class Real> struct PairLaw {
  void (*queue)(const void *self, const Particles<Real> *p, const PairQueue<Real> *q);
  const void *self;
  Real range;  // how far across a gap it attracts [m]; 0: touching only
  unsigned history;
  void operator()(const Particles<Real> &p, const PairQueue<Real> &q) const { queue(self, &p, &q); }
};

// Other work of the step that may run while the pairs are evaluated (it reads the particles' state and
// writes only its own copies), for particles [lo, hi); none when run is null.
struct PairSideJob {
  void (*run)(void *arg, std::uint32_t lo, std::uint32_t hi) = nullptr;
  void *arg = nullptr;
};

namespace detail {
// Adds a sum of contributions (force x, y, z, torque x, y, z) to particle i's accumulators.
template <class Real> void add_sum(const Particles<Real> &p, std::uint32_t i, const Real *s) {
  p.fx[i] += s[0];
  p.fy[i] += s[1];
  p.fz[i] += s[2];
  p.tx[i] += s[3];
  p.ty[i] += s[4];
  p.tz[i] += s[5];
}

// Adds the running sums (6 a particle) of particles [from, to) to their accumulators and clears them:
// the next call starts from zero sums. Through local pointers that the stores cannot change, so that
// the loop keeps them in registers and vectorises.
template <class Real> void add_sums(const Particles<Real> &p, Real *sums, std::uint32_t from, std::uint32_t to) {
  Real *__restrict fx = p.fx, *__restrict fy = p.fy, *__restrict fz = p.fz, *__restrict tx = p.tx,
                   *__restrict ty = p.ty, *__restrict tz = p.tz, *__restrict s = sums;
  for (std::uint32_t i = from; i < to; ++i) {
    Real *own = s + std::size_t(i) * 6;
    fx[i] += own[0];
    fy[i] += own[1];
    fz[i] += own[2];
    tx[i] += own[3];
    ty[i] += own[4];
    tz[i] += own[5];
    for (int c = 0; c < 6; ++c) own[c] = 0;
  }
}

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
template <class Real> bool neighbour_below(const ListView<Real> &list, std::uint32_t i, std::uint32_t lo) {
  return list.start[i] < list.start[i + 1] && list.nbr[list.start[i]] < lo;
}

// One thread's share of the loop: its range, and where its running sums live.
template <class Real> struct PairSweep {
  std::uint32_t lo, hi;
  Real *sums;                     // 6 per particle, indexed by particle
  std::uint32_t waiting_end = 0;  // no particle from here on waits (found by find_waiting_end)

  // True when particle i (of this range or above) has a lower neighbour in an earlier thread's range
  // (never in the first range).
  bool waits(const ListView<Real> &list, std::uint32_t i) const { return i < waiting_end && below_lo(list, i); }
  // Sets waiting_end past the last particle of the range that waits: they lie near its start (the
  // particles are sorted by cell), so that most tests of waits() end at the first comparison.
  void find_waiting_end(const ListView<Real> &list) {
    waiting_end = 0;
    if (lo > 0)
      for (std::uint32_t i = lo; i < hi; ++i) waiting_end = below_lo(list, i) ? i + 1 : waiting_end;
  }
  bool below_lo(const ListView<Real> &list, std::uint32_t i) const { return neighbour_below(list, i, lo); }
  // Adds contribution (f, t) of entry k (k_of() gives it; only records need it) to particle i: to its
  // running sum when the sweep keeps its order, else as the entry's record.
  template <class EntryOf>
  void add(const ListView<Real> &list, std::uint32_t i, EntryOf k_of, const Vec3<Real> &f, const Vec3<Real> &t) {
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
template <class Real> std::uint32_t upper_entry(const ListView<Real> &list, std::uint32_t i, std::uint32_t j) {
  return static_cast<std::uint32_t>(std::lower_bound(list.nbr + list.upper[i], list.nbr + list.start[i + 1], j) -
                                    list.nbr);
}

// The most history values per contact the loop that evaluates each pair once copies into its queues
// (a law keeping more has every entry evaluated).
inline constexpr unsigned queued_history_max = 16;

// A queue of pairs of one thread, handed to the law when full or at the end.
template <class Real> struct PairBatch {
  static constexpr int capacity = 64;
  // Pairs filtered between checks of the room left: a chunk starts with at most capacity - chunk queued,
  // so the filter's stores stay within capacity + chunk (filter_packed's four-lane stores within capacity).
  static constexpr int chunk = 16;
  static_assert(chunk % 4 == 0, "filter_packed takes four candidates at a time");
  std::uint32_t i[capacity + chunk], j[capacity + chunk], entry[capacity + chunk];
  Real dx[capacity + chunk], dy[capacity + chunk], dz[capacity + chunk];
  Real fi[6 * capacity], fj[6 * capacity];   // force and torque on i, then on j, `capacity` apart
  Real hist[queued_history_max * capacity];  // each pair once: the pairs' history, in queue order

  static constexpr int lanes = 8;  // the widest vector of the law's loop (AVX-512, double)

  // Moves the queued pairs [from, to) to the front of the queue; returns how many there are.
  int keep(int from, int to) {
    for (int q = from; q < to; ++q) {
      i[q - from] = i[q];
      j[q - from] = j[q];
      entry[q - from] = entry[q];
      dx[q - from] = dx[q];
      dy[q - from] = dy[q];
      dz[q - from] = dz[q];
    }
    return to - from;
  }
  PairQueue<Real> queue(int size, const ListView<Real> &list, bool both) {
    return {std::uint32_t(size), std::uint32_t(capacity), i, j, dx, dy, dz, entry, both ? hist : list.hist, fi,
            both ? fj : nullptr};
  }
  // Evaluates the first `size` queued pairs (each pair once), keeps the mirror entries' history, and adds
  // their contributions in queue order.
  void flush(int size, const PairLaw<Real> &law, const Particles<Real> &p, const ListView<Real> &list,
             PairSweep<Real> &sweep) {
    if (size == 0) return;
    const unsigned history = law.history;
    // the copies, compiled for the counts the laws keep (unrolled), and for any other
    auto by_count = [&](auto &&copy) {
      if (history == 3) copy(std::integral_constant<unsigned, 3>{});
      else if (history == 6) copy(std::integral_constant<unsigned, 6>{});
      else if (history > 0) copy(history);
    };
    by_count([&](auto count) {  // the law reads and writes the history in queue order
      for (int q = 0; q < size; ++q) {
        const Real *e = list.hist + std::size_t(entry[q]) * count;
        for (unsigned c = 0; c < count; ++c) hist[q * count + c] = e[c];
      }
    });
    law(p, queue(size, list, true));
    by_count([&](auto count) {
      for (int q = 0; q < size; ++q) {
        const Real *h = hist + q * count;
        Real *e = list.hist + std::size_t(entry[q]) * count,
             *m = list.hist + std::size_t(list.mirror[entry[q]]) * count;
        for (unsigned c = 0; c < count; ++c) {
          e[c] = h[c];
          m[c] = -h[c];
        }
      }
    });
    for (int q = 0; q < size; ++q) {
      const std::uint32_t pi = i[q], pj = j[q];
      // records only: the entry, looked up (rare: particles at the border of a thread's range)
      auto entry_of = [&] { return law.history ? entry[q] : upper_entry(list, pi, pj); };
      sweep.add(list, pi, entry_of, {fi[q], fi[capacity + q], fi[2 * capacity + q]},
                {fi[3 * capacity + q], fi[4 * capacity + q], fi[5 * capacity + q]});
      sweep.add(list, pj, [&] { return list.mirror[entry_of()]; }, {fj[q], fj[capacity + q], fj[2 * capacity + q]},
                {fj[3 * capacity + q], fj[4 * capacity + q], fj[5 * capacity + q]});
    }
  }
};

// Adds particle i's records, in list order, to its accumulators, and clears them for the next call.
template <class Real> void add_records(const Particles<Real> &p, const ListView<Real> &list, std::uint32_t i) {
  Real s[6] = {0, 0, 0, 0, 0, 0};
  for (std::uint32_t k = list.start[i]; k < list.start[i + 1]; ++k) {
    Real *r = list.scratch + std::size_t(k) * 6;
    for (int c = 0; c < 6; ++c) {
      s[c] += r[c];
      r[c] = 0;
    }
  }
  add_sum(p, i, s);
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
void add_waiting_records(const Particles<Real> &p, const ListView<Real> &list, const WaitingSpan *spans,
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

// The pairs of entries `apart[0 .. n)` (their entries (i, j)) have left the law's reach since their last
// filter: a pair whose history holds any value forgets it, in both entries. Some hold none (the law
// left them at zero): a read, where clearing every entry would write both.
template <class Real>
void forget_apart(const ListView<Real> &list, unsigned history, const std::uint32_t *apart, int n) {
  for (int a = 0; a < n; ++a) {
    Real *h = list.hist + std::size_t(apart[a]) * history;
    if (!any_value(h, history)) continue;
    Real *m = list.hist + std::size_t(list.mirror[apart[a]]) * history;
    for (unsigned c = 0; c < history; ++c) h[c] = m[c] = 0;
  }
}

// One thread's sweep over its range, compiled once per combination of periodic axes (with or without
// a gap the law reaches across, and history) so that the filter has no branch on them.
// With `packed` (double, AVX2 and up: the particles' positions and radii, packed) the filter takes four candidates at a
// time (filter_packed), the scalar filter the rest.
template <bool PX, bool PY, bool PZ, bool Gap, bool History, class Real>
void sweep_pairs(const PairLaw<Real> &law, const Particles<Real> &p, const ListView<Real> &list, const Real *packed,
                 PairSweep<Real> &shared_sweep) {
  PairSweep<Real> sweep = shared_sweep;  // a copy the stores into the queue cannot alias: kept in registers
  const Real lx = p.box_hi[0] - p.box_lo[0], ly = p.box_hi[1] - p.box_lo[1], lz = p.box_hi[2] - p.box_lo[2];
  const Real *x = p.x, *y = p.y, *z = p.z, *r = p.r;
  const std::uint32_t *pair_i = list.pair_i, *pair_j = list.pair_j, *pair_entry = list.pair_entry;
  std::uint32_t apart[PairBatch<Real>::chunk];  // History: the entries of a chunk's pairs out of reach
  std::uint32_t done = sweep.lo;                // the particles below this one got their sums (or wait for the barrier)
  auto finish_up_to = [&](std::uint32_t end) {
    const std::uint32_t checked = std::max(done, std::min(end, sweep.waiting_end));  // none waits from here on
    for (; done < checked; ++done)
      if (!sweep.waits(list, done)) add_sums(p, sweep.sums, done, done + 1);
    if (done < end) add_sums(p, sweep.sums, done, end);
    done = std::max(done, end);
  };
  using Batch = PairBatch<Real>;
  Batch batch;
  int queued = 0;
  const std::uint32_t end = list.first_pair[sweep.hi];
  for (std::uint32_t u = list.first_pair[sweep.lo]; u < end;) {
    // a chunk of pairs, each written to the queue and kept (counted) only when touching: no branch
    const std::uint32_t stop = min(end, u + std::uint32_t(Batch::chunk));
    int parted = 0;
#if SPREADMAP_SIMD_LEVELS
    if constexpr (std::is_same_v<Real, double>)
      if (packed) {
        const double length[3] = {lx, ly, lz};
        const FilterQueue to{batch.i, batch.j, batch.entry, batch.dx, batch.dy, batch.dz};
        u = filter_packed<PX, PY, PZ, Gap, History>(packed, pair_i, pair_j, pair_entry, u, stop, length, law.range, to,
                                                    queued, list.in_reach, apart, parted);
      }
#else
    (void)packed;
#endif
    for (; u < stop; ++u) {
      const std::uint32_t i = pair_i[u], j = pair_j[u];
      const Real ddx = wrap_axis<PX>(x[i] - x[j], lx), ddy = wrap_axis<PY>(y[i] - y[j], ly),
                 ddz = wrap_axis<PZ>(z[i] - z[j], lz);
      const Real reach = Gap ? r[i] + r[j] + law.range : r[i] + r[j];
      const bool near = ddx * ddx + ddy * ddy + ddz * ddz < reach * reach;
      batch.i[queued] = i;
      batch.j[queued] = j;
      batch.dx[queued] = ddx;
      batch.dy[queued] = ddy;
      batch.dz[queued] = ddz;
      if constexpr (History) {
        const std::uint32_t k = pair_entry[u];
        batch.entry[queued] = k;
        apart[parted] = k;
        parted += !near && list.in_reach[u] ? 1 : 0;
        list.in_reach[u] = near ? 1 : 0;
      }
      queued += near ? 1 : 0;
    }
    if constexpr (History) forget_apart(list, law.history, apart, parted);
    if (queued > Batch::capacity - Batch::chunk) {
      // a whole number of the law's vectors (no scalar remainder in its loop); the rest waits in the queue
      const int whole = queued / Batch::lanes * Batch::lanes;
      batch.flush(whole, law, p, list, sweep);
      queued = batch.keep(whole, queued);
      // every pair of the particles before is evaluated
      finish_up_to(queued > 0 ? batch.i[0] : (u < end ? pair_i[u] : sweep.hi));
    }
  }
  batch.flush(queued, law, p, list, sweep);
  finish_up_to(sweep.hi);
  shared_sweep = sweep;
}

// Every entry of particles [lo, hi), each with its own history: entries out of reach forget theirs,
// the others are queued; each particle's contributions are added in list order, then to the particle
// (the bits of pair_forces_on).
template <bool Gap, class Real>
void sweep_entries(const PairLaw<Real> &law, const Particles<Real> &p, const ListView<Real> &list, std::uint32_t lo,
                   std::uint32_t hi) {
  using Batch = PairBatch<Real>;
  Batch batch;
  const Real lx = p.box_hi[0] - p.box_lo[0], ly = p.box_hi[1] - p.box_lo[1], lz = p.box_hi[2] - p.box_lo[2];
  const unsigned history = law.history;
  std::uint32_t current = hi;  // the particle whose sum is open (hi: none)
  Real sum[6] = {0, 0, 0, 0, 0, 0};
  auto close = [&] {
    if (current == hi) return;
    add_sum(p, current, sum);
  };
  auto flush = [&](int size) {
    if (size == 0) return;
    law(p, batch.queue(size, list, false));
    for (int q = 0; q < size; ++q) {
      if (batch.i[q] != current) {
        close();
        current = batch.i[q];
        for (Real &s : sum) s = 0;
      }
      for (int c = 0; c < 6; ++c) sum[c] += batch.fi[c * Batch::capacity + q];
    }
  };
  int queued = 0;
  for (std::uint32_t i = lo; i < hi; ++i) {
    for (std::uint32_t k = list.start[i]; k < list.start[i + 1]; ++k) {
      const std::uint32_t j = list.nbr[k];
      const Real dx = wrap(p.x[i] - p.x[j], lx, p.periodic[0] != 0), dy = wrap(p.y[i] - p.y[j], ly, p.periodic[1] != 0),
                 dz = wrap(p.z[i] - p.z[j], lz, p.periodic[2] != 0);
      const Real reach = Gap ? p.r[i] + p.r[j] + law.range : p.r[i] + p.r[j];
      if (dx * dx + dy * dy + dz * dz >= reach * reach) {
        Real *h = list.hist + std::size_t(k) * history;
        for (unsigned q = 0; q < history; ++q) h[q] = 0;  // apart: forget
        continue;
      }
      batch.i[queued] = i;
      batch.j[queued] = j;
      batch.entry[queued] = k;
      batch.dx[queued] = dx;
      batch.dy[queued] = dy;
      batch.dz[queued] = dz;
      if (++queued == Batch::capacity) {
        flush(queued);
        queued = 0;
      }
    }
  }
  flush(queued);
  close();
}
}  // namespace detail

// The pair forces of a law without history or whose history mirrors, each touching pair evaluated once
// (list.once()). Each thread runs `side` for its particles after its sweep, timed with it: the
// balance of the sweeps then takes it in, and the particles' data stays in the core that owns them.
template <class Real>
void pair_forces_once(const PairLaw<Real> &law, const Particles<Real> &p, const ListView<Real> &list,
                      PairSideJob side = {}) {
  const bool px = p.periodic[0] != 0, py = p.periodic[1] != 0, pz = p.periodic[2] != 0, gap = law.range > 0;
  const Team *team_of_thread = this_thread_team();
  // the spheres packed for the filter of four candidates at a time, where it runs
  Real *packed =
      std::is_same_v<Real, double> && filter_packed_built && simd_level() >= SimdLevel::avx2 ? list.packed : nullptr;
  int threads = 1;
  detail::WaitingSpan waiting[PairBalance::max_threads];
  run_team(team_of_thread, [&](TeamSlot team) {
    const int t = team.thread, nt = team.threads;
    if (packed) {  // each thread its share, all of them before any sweep reads one
      const TeamRange mine = team_share(p.n, team);
      with_simd([&] { pack_spheres(p, std::uint32_t(mine.lo), std::uint32_t(mine.hi), packed); });
      team_barrier(team_of_thread);
    }
    const auto began = std::chrono::steady_clock::now();
    detail::PairSweep<Real> sweep;
    detail::entry_balanced_range(list.start, p.n, t, nt, list.balance, sweep.lo, sweep.hi);
    sweep.sums = list.scratch + std::size_t(list.start[p.n]) * 6;  // after the records; zero on entry and exit
    sweep.find_waiting_end(list);
    auto sweep_with = [&]<bool PX, bool PY, bool PZ>() {
      with_simd([&] {
        if (law.history) {
          if (gap) detail::sweep_pairs<PX, PY, PZ, true, true>(law, p, list, packed, sweep);
          else detail::sweep_pairs<PX, PY, PZ, false, true>(law, p, list, packed, sweep);
        } else {
          if (gap) detail::sweep_pairs<PX, PY, PZ, true, false>(law, p, list, packed, sweep);
          else detail::sweep_pairs<PX, PY, PZ, false, false>(law, p, list, packed, sweep);
        }
      });
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
    if (side.run) side.run(side.arg, sweep.lo, sweep.hi);
    const auto swept = std::chrono::steady_clock::now();
    const bool shared = nt <= PairBalance::max_threads;
    if (shared) waiting[t] = {sweep.lo, std::max(sweep.lo, sweep.waiting_end)};
    team_barrier(team_of_thread);
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

// The pair forces with every list entry evaluated (laws with history, or a list without mirrors).
template <class Real>
void pair_forces_every_entry(const PairLaw<Real> &law, const Particles<Real> &p, const ListView<Real> &list) {
  run_team(this_thread_team(), [&](TeamSlot team) {
    const TeamRange r = team_share(p.n, team);
    const auto lo = static_cast<std::uint32_t>(r.lo), hi = static_cast<std::uint32_t>(r.hi);
    if (law.range > 0) detail::sweep_entries<true>(law, p, list, lo, hi);
    else detail::sweep_entries<false>(law, p, list, lo, hi);
  });
}

}  // namespace spreadmap::engine
