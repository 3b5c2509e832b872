// The filter of the loop that evaluates each pair once (engine/pair_loops.hpp), four candidate pairs at
// a time with AVX2. Each sphere's position and radius lie side by side in 32 bytes (the loop packs them
// at the start of each call: `packed`), so that four candidates take eight loads and a transpose where
// the scalar filter takes 32 scattered loads and about 36 instructions a candidate. (Gathers from the
// separate arrays, 8 lanes with AVX-512, ran 7-11 % slower than the scalar filter on an AMD EPYC.) The
// pairs in reach are compressed into the queue through a table of lane orders. Every lane performs the
// scalar filter's operations in its order (minimum image, reach, distance squared), so the pairs kept
// and the separations queued are the same bits.
#pragma once
#include <spreadmap/batch.hpp>
#include <spreadmap/simd.hpp>

#include <cstddef>
#include <cstdint>
#include <cstring>
#if SPREADMAP_SIMD_LEVELS
#include <immintrin.h>
#endif

namespace spreadmap::engine {

// Copies particles [lo, hi)'s x, y, z and r into `packed`, 4 values a particle.
template <class Real> void pack_spheres(const Particles<Real> &p, std::uint32_t lo, std::uint32_t hi, Real *packed) {
  for (std::uint32_t i = lo; i < hi; ++i) {
    Real *sphere = packed + std::size_t(i) * 4;
    sphere[0] = p.x[i];
    sphere[1] = p.y[i];
    sphere[2] = p.z[i];
    sphere[3] = p.r[i];
  }
}

// Where the filter appends the pairs it keeps: the queue's arrays (each with room for 4 values past the
// last pair kept: a compressed store writes all four lanes).
struct FilterQueue {
  std::uint32_t *i, *j, *entry;
  double *dx, *dy, *dz;
};

#if SPREADMAP_SIMD_LEVELS
inline constexpr bool filter_packed_built = true;
namespace detail {
// For each mask of 4 lanes, the lanes set, in order, as indices of 32-bit lanes: of 4 values of 32 bits
// (index k), and of 4 values of 64 bits (indices 2k, 2k + 1).
struct LaneOrders {
  std::uint32_t of32[16][8], of64[16][8];
};
constexpr LaneOrders lane_orders() {
  LaneOrders o{};
  for (int mask = 0; mask < 16; ++mask) {
    int kept = 0;
    for (int k = 0; k < 4; ++k) {
      if (!(mask >> k & 1)) continue;
      o.of32[mask][kept] = std::uint32_t(k);
      o.of64[mask][2 * kept] = std::uint32_t(2 * k);
      o.of64[mask][2 * kept + 1] = std::uint32_t(2 * k + 1);
      ++kept;
    }
  }
  return o;
}
inline constexpr LaneOrders lane_order = lane_orders();

// For each mask of 4 lanes, its lanes as 4 bytes of 0 or 1 (lane k in byte k, as x86 stores them).
struct LaneBytes {
  std::uint32_t of[16];
};
constexpr LaneBytes lane_bytes_table() {
  LaneBytes b{};
  for (int mask = 0; mask < 16; ++mask)
    for (int k = 0; k < 4; ++k) b.of[mask] |= std::uint32_t(mask >> k & 1) << (8 * k);
  return b;
}
inline constexpr LaneBytes lane_bytes = lane_bytes_table();
// The mask of 4 bytes of 0 or 1 (byte k: lane k).
inline int mask_of_bytes(std::uint32_t bytes) {
  return int((bytes & 1u) | (bytes >> 7 & 2u) | (bytes >> 14 & 4u) | (bytes >> 21 & 8u));
}

// wrap_axis<true> on four lanes: (d - (d > h ? L : 0)) - (d < -h ? -L : 0).
__attribute__((target("arch=x86-64-v3"))) inline __m256d wrap_lanes(__m256d d, double length) {
  const double half = 0.5 * length;
  const __m256d up = _mm256_and_pd(_mm256_cmp_pd(d, _mm256_set1_pd(half), _CMP_GT_OQ), _mm256_set1_pd(length));
  const __m256d down = _mm256_and_pd(_mm256_cmp_pd(d, _mm256_set1_pd(-half), _CMP_LT_OQ), _mm256_set1_pd(-length));
  return _mm256_sub_pd(_mm256_sub_pd(d, up), down);
}

// Stores the lanes of v set in `mask`, in order, at `to`.
__attribute__((target("arch=x86-64-v3"))) inline void store_kept(std::uint32_t *to, __m128i v, int mask) {
  const __m256i order = _mm256_loadu_si256(reinterpret_cast<const __m256i *>(lane_order.of32[mask]));
  const __m256i kept = _mm256_permutevar8x32_epi32(_mm256_castsi128_si256(v), order);
  _mm_storeu_si128(reinterpret_cast<__m128i *>(to), _mm256_castsi256_si128(kept));
}
__attribute__((target("arch=x86-64-v3"))) inline void store_kept(double *to, __m256d v, int mask) {
  const __m256i order = _mm256_loadu_si256(reinterpret_cast<const __m256i *>(lane_order.of64[mask]));
  _mm256_storeu_pd(to, _mm256_castsi256_pd(_mm256_permutevar8x32_epi32(_mm256_castpd_si256(v), order)));
}

// One candidate's separation (x, y, z) with the sum of radii in the last lane.
__attribute__((target("arch=x86-64-v3"))) inline __m256d packed_pair(const double *packed, std::uint32_t i,
                                                                     std::uint32_t j) {
  const __m256d a = _mm256_load_pd(packed + std::size_t(i) * 4), b = _mm256_load_pd(packed + std::size_t(j) * 4);
  return _mm256_blend_pd(_mm256_sub_pd(a, b), _mm256_add_pd(a, b), 0b1000);
}
}  // namespace detail

// Filters the candidate pairs u, u + 4, ... of [u, stop) while four remain: appends those within reach
// (distance below r_i + r_j, plus `range` with Gap) to the queue at `queued`; with History, appends the
// entries of those out of reach that were in reach at their last filter (in_reach[u], 1 or 0: only they
// may hold history) to `apart` at `parted`, and sets in_reach[u] for each. Returns the first candidate
// left (fewer than 4 remain). `packed` is 32-byte aligned.
template <bool PX, bool PY, bool PZ, bool Gap, bool History>
__attribute__((target("arch=x86-64-v3"))) inline std::uint32_t filter_packed(
    const double *packed, const std::uint32_t *pair_i, const std::uint32_t *pair_j, const std::uint32_t *pair_entry,
    std::uint32_t u, std::uint32_t stop, const double length[3], double range, const FilterQueue &q, int &queued,
    std::uint8_t *in_reach, std::uint32_t *apart, int &parted) {
  for (; u + 4 <= stop; u += 4) {
    const std::uint32_t *i = pair_i + u, *j = pair_j + u;
    const __m256d a = detail::packed_pair(packed, i[0], j[0]), b = detail::packed_pair(packed, i[1], j[1]),
                  c = detail::packed_pair(packed, i[2], j[2]), d = detail::packed_pair(packed, i[3], j[3]);
    // transpose: one vector per component, one lane per candidate
    const __m256d ab_xz = _mm256_unpacklo_pd(a, b), ab_yr = _mm256_unpackhi_pd(a, b), cd_xz = _mm256_unpacklo_pd(c, d),
                  cd_yr = _mm256_unpackhi_pd(c, d);
    __m256d dx = _mm256_permute2f128_pd(ab_xz, cd_xz, 0x20), dz = _mm256_permute2f128_pd(ab_xz, cd_xz, 0x31),
            dy = _mm256_permute2f128_pd(ab_yr, cd_yr, 0x20), reach = _mm256_permute2f128_pd(ab_yr, cd_yr, 0x31);
    if constexpr (PX) dx = detail::wrap_lanes(dx, length[0]);
    if constexpr (PY) dy = detail::wrap_lanes(dy, length[1]);
    if constexpr (PZ) dz = detail::wrap_lanes(dz, length[2]);
    if constexpr (Gap) reach = _mm256_add_pd(reach, _mm256_set1_pd(range));
    const __m256d d2 =
        _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(dx, dx), _mm256_mul_pd(dy, dy)), _mm256_mul_pd(dz, dz));
    const int near = _mm256_movemask_pd(_mm256_cmp_pd(d2, _mm256_mul_pd(reach, reach), _CMP_LT_OQ));
    detail::store_kept(q.i + queued, _mm_loadu_si128(reinterpret_cast<const __m128i *>(i)), near);
    detail::store_kept(q.j + queued, _mm_loadu_si128(reinterpret_cast<const __m128i *>(j)), near);
    detail::store_kept(q.dx + queued, dx, near);
    detail::store_kept(q.dy + queued, dy, near);
    detail::store_kept(q.dz + queued, dz, near);
    if constexpr (History) {
      const __m128i entries = _mm_loadu_si128(reinterpret_cast<const __m128i *>(pair_entry + u));
      detail::store_kept(q.entry + queued, entries, near);
      std::uint32_t before;
      std::memcpy(&before, in_reach + u, 4);
      const int left = (near ^ 0b1111) & detail::mask_of_bytes(before);
      detail::store_kept(apart + parted, entries, left);
      parted += __builtin_popcount(unsigned(left));
      std::memcpy(in_reach + u, &detail::lane_bytes.of[near], 4);
    }
    queued += __builtin_popcount(unsigned(near));
  }
  return u;
}
#else
inline constexpr bool filter_packed_built = false;
#endif

}  // namespace spreadmap::engine
