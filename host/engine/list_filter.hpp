// The CPU list build's search (engine/neighbour_list.cpp), four candidates at a time with AVX2. The
// particles are sorted by cell, so the candidates of a particle are a few runs of consecutive indices
// (the cells around its own, a row of cells one run: neighbour_runs): four candidates are a plain load from
// each of x, y, z and r, where the scalar search (list_neighbours) takes them one by one with a
// branch on each periodic axis. Every lane performs list_neighbours' operations in its order
// (minimum image, reach, distance squared), so the same neighbours are listed in the same order.
#pragma once
#include <engine/cell_grid.hpp>
#include <engine/minimum_image.hpp>
#include <engine/pair_filter.hpp>

#include <cstdint>
#include <utility>

namespace spreadmap::engine {

// Joins each range of `ranges` (in increasing begin) with the next where it ends at the next one's
// begin: the same particles in the same order, in fewer runs.
inline void join_touching(CellRanges &ranges) {
  if (ranges.n == 0) return;
  int joined = 0;
  for (int q = 1; q < ranges.n; ++q) {
    if (ranges.begin[q] == ranges.end[joined]) {
      ranges.end[joined] = ranges.end[q];
    } else {
      ++joined;
      ranges.begin[joined] = ranges.begin[q];
      ranges.end[joined] = ranges.end[q];
    }
  }
  ranges.n = joined + 1;
}

// The particles of the cells around `cell` (itself included) as neighbour_ranges and join_touching
// give them, found row by row: along the grid's fastest axis the cells of a row lie side by side in
// the sorted particles, so a row is one run (two where a periodic axis wraps) from two reads of
// cell_start, where neighbour_ranges reads and sorts each of up to 27 cells.
template <class Real>
CellRanges neighbour_runs(const CellGrid<Real> &grid, std::uint32_t cell, const std::uint32_t *cell_start) {
  int cc[3];
  grid.coords(cell, cc);
  const int fast = grid.order[0], mid = grid.order[1], slow = grid.order[2];
  int along[3], am[3], as[3];
  const int kf = detail::axis_neighbours(cc[fast], grid.n[fast], grid.periodic[fast], along);
  const int km = detail::axis_neighbours(cc[mid], grid.n[mid], grid.periodic[mid], am);
  const int ks = detail::axis_neighbours(cc[slow], grid.n[slow], grid.periodic[slow], as);
  for (int k = 1; k < kf; ++k)  // at most three, in increasing order
    for (int q = k; q > 0 && along[q - 1] > along[q]; --q) std::swap(along[q - 1], along[q]);
  CellRanges r;
  for (int a = 0; a < ks; ++a)
    for (int b = 0; b < km; ++b) {
      int c[3];
      c[slow] = as[a];
      c[mid] = am[b];
      // the row's cells in increasing order, in runs of consecutive ones
      for (int first = 0; first < kf;) {
        int last = first;
        while (last + 1 < kf && along[last + 1] == along[last] + 1) ++last;
        c[fast] = along[first];
        const std::size_t lo = grid.index(c);
        c[fast] = along[last];
        r.insert(cell_start[lo], cell_start[grid.index(c) + 1]);
        first = last + 1;
      }
    }
  join_touching(r);
  return r;
}

#if SPREADMAP_SIMD_LEVELS
// list_neighbours(i, ..., mobile = null, ..., first) for double: the neighbours j >= first (> i) of
// particle i among `ranges`, written in increasing index to `out` (room for every candidate and 4 more:
// a compressed store writes four lanes). Returns how many there are.
template <bool PX, bool PY, bool PZ>
__attribute__((target("arch=x86-64-v3"))) std::uint32_t list_neighbours_four(std::uint32_t i, const double *x,
                                                                             const double *y, const double *z,
                                                                             const double *r, const double len[3],
                                                                             double skin, const CellRanges &ranges,
                                                                             std::uint32_t *out, std::uint32_t first) {
  const double xi = x[i], yi = y[i], zi = z[i], ri = r[i];
  const __m256d vxi = _mm256_set1_pd(xi), vyi = _mm256_set1_pd(yi), vzi = _mm256_set1_pd(zi), vri = _mm256_set1_pd(ri),
                vskin = _mm256_set1_pd(skin);
  const __m128i step = _mm_set1_epi32(4);
  std::uint32_t count = 0;
  for (int q = 0; q < ranges.n; ++q) {
    std::uint32_t j = ranges.begin[q] > first ? ranges.begin[q] : first;
    const std::uint32_t end = ranges.end[q];
    __m128i index = _mm_add_epi32(_mm_set1_epi32(int(j)), _mm_setr_epi32(0, 1, 2, 3));
    for (; j + 4 <= end; j += 4, index = _mm_add_epi32(index, step)) {
      __m256d dx = _mm256_sub_pd(vxi, _mm256_loadu_pd(x + j)), dy = _mm256_sub_pd(vyi, _mm256_loadu_pd(y + j)),
              dz = _mm256_sub_pd(vzi, _mm256_loadu_pd(z + j));
      if constexpr (PX) dx = detail::wrap_lanes(dx, len[0]);
      if constexpr (PY) dy = detail::wrap_lanes(dy, len[1]);
      if constexpr (PZ) dz = detail::wrap_lanes(dz, len[2]);
      const __m256d reach = _mm256_add_pd(_mm256_add_pd(vri, _mm256_loadu_pd(r + j)), vskin);
      const __m256d d2 =
          _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(dx, dx), _mm256_mul_pd(dy, dy)), _mm256_mul_pd(dz, dz));
      const int near = _mm256_movemask_pd(_mm256_cmp_pd(d2, _mm256_mul_pd(reach, reach), _CMP_LT_OQ));
      detail::store_kept(out + count, index, near);
      count += unsigned(__builtin_popcount(unsigned(near)));
    }
    for (; j < end; ++j) {
      const double dx = wrap_axis<PX>(xi - x[j], len[0]), dy = wrap_axis<PY>(yi - y[j], len[1]),
                   dz = wrap_axis<PZ>(zi - z[j], len[2]);
      const double reach = (ri + r[j]) + skin;
      out[count] = j;
      count += dx * dx + dy * dy + dz * dz < reach * reach ? 1u : 0u;
    }
  }
  return count;
}
#endif

}  // namespace spreadmap::engine
