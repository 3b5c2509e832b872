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
// Pass 1, per thread over a range of particles balanced by list entries: the upper entries (j > i)
// are tested; touching ones are queued and evaluated in short loops over up to 64 contacts
// (kinematics, law, contributions), so that the core overlaps many contacts' sqrt/div chains. The
// two contributions of a pair (for i and for j) are appended to the thread's run of records, and
// slot[k] names entry k's record, 0 (an all-zero record) when not touching. Thread t's run starts at
// record 1 + 2 * (entries before its range), so runs never overlap and the touched records stay
// compact in memory. Pass 2: each particle adds the records of its entries in list order (adding +0
// leaves a sum unchanged, so untouched entries need no branch).
#pragma once
#include <spreadmap/contact.hpp>

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

// A queue of touching pairs of one thread, evaluated in stages when full or at the end.
template <class Law, class Real> struct PairBatch {
  static constexpr int capacity = 64;
  std::uint32_t i[capacity], j[capacity], k[capacity];
  Vec3<Real> d[capacity];
  Real dist2[capacity];
  ContactState<Real> state[capacity];
  ContactForce<Real> force[capacity];

  // Evaluates the first `size` queued pairs; writes their records from `next` on and returns the
  // next free record.
  std::size_t flush(int size, std::size_t next, const Law &law, const Particles<Real> &p,
                    const PairList<Real> &list) {
    for (int q = 0; q < size; ++q) state[q] = pair_contact_state(p, i[q], j[q], d[q], dist2[q]);
    for (int q = 0; q < size; ++q) force[q] = law(state[q], static_cast<Real *>(nullptr));
    for (int q = 0; q < size; ++q) {
      const ContactState<Real> &c = state[q];
      const ContactForce<Real> &f = force[q];
      const ContactForce<Real> mirrored{f.normal, -f.tangent, -f.torque};  // the law's answer seen from j
      Vec3<Real> fi{0, 0, 0}, ti{0, 0, 0}, fj{0, 0, 0}, tj{0, 0, 0};
      accumulate(f, c.normal, p.r[i[q]], fi, ti);
      accumulate(mirrored, -c.normal, p.r[j[q]], fj, tj);
      Real *r = list.scratch + next * 6;
      r[0] = fi.x; r[1] = fi.y; r[2] = fi.z; r[3] = ti.x; r[4] = ti.y; r[5] = ti.z;
      r[6] = fj.x; r[7] = fj.y; r[8] = fj.z; r[9] = tj.x; r[10] = tj.y; r[11] = tj.z;
      list.slot[k[q]] = static_cast<std::uint32_t>(next);
      list.slot[list.mirror[k[q]]] = static_cast<std::uint32_t>(next + 1);
      next += 2;
    }
    return next;
  }
};
}  // namespace detail

template <class Law, class Real>
void pair_loop_once(const Law &law, const Particles<Real> &p, const PairList<Real> &list) {
  static_assert(Law::history == 0, "a law with history is evaluated for every entry");
  const Real lx = p.box_hi[0] - p.box_lo[0], ly = p.box_hi[1] - p.box_lo[1], lz = p.box_hi[2] - p.box_lo[2];
  const bool px = p.periodic[0] != 0, py = p.periodic[1] != 0, pz = p.periodic[2] != 0;  // not reloaded per store
#pragma omp parallel
  {
#ifdef _OPENMP
    const int t = omp_get_thread_num(), nt = omp_get_num_threads();
#else
    const int t = 0, nt = 1;
#endif
    std::uint32_t lo, hi;
    detail::entry_balanced_range(list.start, p.n, t, nt, lo, hi);
    detail::PairBatch<Law, Real> batch;
    int queued = 0;
    std::size_t next = 1 + 2 * std::size_t(list.start[lo]);
    for (std::uint32_t i = lo; i < hi; ++i) {
      const Real xi = p.x[i], yi = p.y[i], zi = p.z[i], ri = p.r[i];
      const std::uint32_t begin = list.start[i], end = list.start[i + 1];
      std::uint32_t lower = 0;  // neighbours are listed by index: the upper ones follow the lower ones
      for (std::uint32_t k = begin; k < end; ++k) lower += list.nbr[k] < i ? 1u : 0u;
      for (std::uint32_t k = begin + lower; k < end; ++k) {
        const std::uint32_t j = list.nbr[k];
        const Vec3<Real> d{wrap(xi - p.x[j], lx, px), wrap(yi - p.y[j], ly, py), wrap(zi - p.z[j], lz, pz)};
        const Real dist2 = dot(d, d), reach = ri + p.r[j];
        list.slot[k] = 0;
        list.slot[list.mirror[k]] = 0;
        batch.i[queued] = i; batch.j[queued] = j; batch.k[queued] = k; batch.d[queued] = d; batch.dist2[queued] = dist2;
        queued += dist2 < reach * reach ? 1 : 0;  // kept only when touching, without a branch
        if (queued == batch.capacity) {
          next = batch.flush(queued, next, law, p, list);
          queued = 0;
        }
      }
    }
    batch.flush(queued, next, law, p, list);
#pragma omp barrier
    for (std::uint32_t i = lo; i < hi; ++i) {
      Real s[6] = {0, 0, 0, 0, 0, 0};
      for (std::uint32_t k = list.start[i]; k < list.start[i + 1]; ++k) {
        const Real *r = list.scratch + std::size_t(list.slot[k]) * 6;
        for (int c = 0; c < 6; ++c) s[c] += r[c];
      }
      p.fx[i] += s[0]; p.fy[i] += s[1]; p.fz[i] += s[2];
      p.tx[i] += s[3]; p.ty[i] += s[4]; p.tz[i] += s[5];
    }
  }
}

}  // namespace spreadmap
