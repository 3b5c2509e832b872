// Listing the neighbours of one particle: the body of the CPU list build and of the GPU one, so both
// backends list the same pairs in the same order (the order each particle sums its forces in).
#pragma once
#include <engine/cell_grid.hpp>
#include <engine/minimum_image.hpp>
#include <spreadmap/contact.hpp>  // wrap

#include <cstdint>

namespace spreadmap::engine {

// The neighbours j >= first of particle i among the particles of `ranges` (the cells around i's
// cell): |x_i - x_j| < r_i + r_j + skin (minimum image along periodic axes), j != i, and, when
// `mobile` is given, not both asleep. Returns how many there are and writes them, in increasing
// index, to out[0, capacity): the CPU passes room for every candidate, the GPU counts first
// (capacity 0) and then fills exactly. The test is symmetric in i and j, so the list is too: the CPU
// lists only j > i (first = i + 1) and finds the rest by symmetry.
template <class Real>
SM_HD std::uint32_t list_neighbours(std::uint32_t i, const Real *x, const Real *y, const Real *z, const Real *r,
                                    const Real *mobile, const Real len[3], const bool per[3], Real skin,
                                    const CellRanges &ranges, std::uint32_t *out, std::uint32_t capacity,
                                    std::uint32_t first = 0) {
  const Real xi = x[i], yi = y[i], zi = z[i], ri = r[i];
  const Real awake_i = mobile ? mobile[i] : Real(1);
  std::uint32_t count = 0;
  for (int q = 0; q < ranges.n; ++q)
    for (std::uint32_t j = ranges.begin[q] > first ? ranges.begin[q] : first; j < ranges.end[q]; ++j) {
      const Real dx = wrap(xi - x[j], len[0], per[0]);
      const Real dy = wrap(yi - y[j], len[1], per[1]);
      const Real dz = wrap(zi - z[j], len[2], per[2]);
      const Real reach = (ri + r[j]) + skin;
      const bool listed = !mobile || awake_i > 0 || mobile[j] > 0;
      if (count < capacity) out[count] = j;  // kept only if counted: a later neighbour overwrites it
      count += (dx * dx + dy * dy + dz * dz < reach * reach) & (j != i) & listed ? 1u : 0u;
    }
  return count;
}

// 1 when particles i and j overlap by more than `limit` times the smaller diameter, else 0.
template <class Real>
SM_HD std::uint32_t deep_overlap(std::uint32_t i, std::uint32_t j, const Real *x, const Real *y, const Real *z,
                                 const Real *r, const Real len[3], const bool per[3], Real limit) {
  const Real dx = wrap(x[i] - x[j], len[0], per[0]), dy = wrap(y[i] - y[j], len[1], per[1]),
             dz = wrap(z[i] - z[j], len[2], per[2]);
  const Real smaller = r[i] < r[j] ? r[i] : r[j];
  const Real allowed = (r[i] + r[j]) - 2 * limit * smaller;  // centre distance at the limit
  return dx * dx + dy * dy + dz * dz < allowed * allowed ? 1u : 0u;
}

// How many of the pairs (pair_i[u], pair_j[u]), u in [lo, hi), overlap by more than `limit` times the
// smaller diameter: deep_overlap over a flat sequence, the periodic axes fixed at compile time and no
// branch, so that the loop vectorises (CPU only).
template <bool PX, bool PY, bool PZ, class Real>
std::uint32_t deep_overlap_pairs(const std::uint32_t *pair_i, const std::uint32_t *pair_j, std::uint64_t lo,
                                 std::uint64_t hi, const Real *x, const Real *y, const Real *z, const Real *r,
                                 const Real len[3], Real limit) {
  std::uint32_t bad = 0;
  for (std::uint64_t u = lo; u < hi; ++u) {
    const std::uint32_t i = pair_i[u], j = pair_j[u];
    const Real dx = wrap_axis<PX>(x[i] - x[j], len[0]),
               dy = wrap_axis<PY>(y[i] - y[j], len[1]),
               dz = wrap_axis<PZ>(z[i] - z[j], len[2]);
    const Real smaller = r[i] < r[j] ? r[i] : r[j];
    const Real allowed = (r[i] + r[j]) - 2 * limit * smaller;
    bad += dx * dx + dy * dy + dz * dz < allowed * allowed ? 1u : 0u;
  }
  return bad;
}

// How many of particle i's listed pairs with a higher index overlap by more than `limit` times the
// smaller diameter (each pair is counted once, by its lower particle: the upper neighbours come last,
// from upper[i] when the list keeps it, else counted).
template <class Real>
SM_HD std::uint32_t deep_overlaps(std::uint32_t i, const Real *x, const Real *y, const Real *z, const Real *r,
                                  const std::uint32_t *start, const std::uint32_t *nbr, const std::uint32_t *upper,
                                  const Real len[3], const bool per[3], Real limit) {
  std::uint32_t k = start[i], bad = 0;
  if (upper) k = upper[i];
  else
    for (std::uint32_t q = start[i]; q < start[i + 1]; ++q) k += nbr[q] < i ? 1u : 0u;
  for (; k < start[i + 1]; ++k) bad += deep_overlap(i, nbr[k], x, y, z, r, len, per, limit);
  return bad;
}

// Particle i's contact history carried from the previous list: each entry (i, j) takes the values of
// the same pair there, found through the particles' indices in the previous list (list_index,
// no_index = 0xffffffff for a particle it did not know); new pairs keep their zeros.
template <class Real>
SM_HD void carry_history(std::uint32_t i, const std::uint32_t *list_index, std::uint32_t old_n,
                         const std::uint32_t *start, const std::uint32_t *nbr, Real *hist,
                         const std::uint32_t *old_start, const std::uint32_t *old_nbr, const Real *old_hist,
                         unsigned history) {
  const std::uint32_t oi = list_index[i];
  if (oi == 0xffffffffu || oi >= old_n) return;
  const std::uint32_t ob = old_start[oi], oe = old_start[oi + 1];
  for (std::uint32_t k = start[i]; k < start[i + 1]; ++k) {
    const std::uint32_t oj = list_index[nbr[k]];
    if (oj == 0xffffffffu) continue;
    for (std::uint32_t ok = ob; ok < oe; ++ok) {
      if (old_nbr[ok] != oj) continue;
      for (unsigned h = 0; h < history; ++h)
        hist[std::size_t(k) * history + h] = old_hist[std::size_t(ok) * history + h];
      break;
    }
  }
}

}  // namespace spreadmap::engine
