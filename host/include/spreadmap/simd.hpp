// The instruction set the hottest CPU loops run with (the pair and wall queues, the kicks, the plane
// overlaps), chosen once per process: with_simd(f) runs f compiled for plain x86-64, for AVX2
// (x86-64-v3) or for AVX-512 (x86-64-v4). Without FMA contraction (-ffp-contract=off, set by the
// build and the SDK) and without reassociation, every level gives the same bits.
//
// The choice: SPREADMAP_SIMD=base|avx2|avx512 when set (capped at what the processor runs), else
// AVX-512 on AMD processors, which run 512-bit vectors at full clock (+10 % on the peers' scene on a
// Zen 5 EPYC), and AVX2 elsewhere (an Intel Xeon ran the AVX-512 loops 20 % slower).
#pragma once
#include <cstdlib>
#include <cstring>

namespace spreadmap {

enum class SimdLevel : int { base = 0, avx2 = 1, avx512 = 2 };

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && !defined(__CUDACC__) && \
    !defined(__SANITIZE_ADDRESS__)
#define SPREADMAP_SIMD_LEVELS 1

// The highest level this processor runs.
inline SimdLevel simd_supported() {
  __builtin_cpu_init();
  if (__builtin_cpu_supports("x86-64-v4")) return SimdLevel::avx512;
  if (__builtin_cpu_supports("x86-64-v3")) return SimdLevel::avx2;
  return SimdLevel::base;
}

inline SimdLevel simd_default() {
  const SimdLevel supported = simd_supported();
  SimdLevel wanted = __builtin_cpu_is("amd") ? SimdLevel::avx512 : SimdLevel::avx2;
  if (const char *env = std::getenv("SPREADMAP_SIMD")) {
    if (!std::strcmp(env, "base")) wanted = SimdLevel::base;
    else if (!std::strcmp(env, "avx2")) wanted = SimdLevel::avx2;
    else if (!std::strcmp(env, "avx512")) wanted = SimdLevel::avx512;
  }
  return wanted < supported ? wanted : supported;
}

namespace detail {
inline SimdLevel &simd_level_slot() {
  static SimdLevel level = simd_default();
  return level;
}
template <class F> __attribute__((target("arch=x86-64-v4"), flatten)) void run_avx512(F &f) { f(); }
template <class F> __attribute__((target("arch=x86-64-v3"), flatten)) void run_avx2(F &f) { f(); }
template <class F> __attribute__((flatten)) void run_base(F &f) { f(); }
}  // namespace detail

inline SimdLevel simd_level() { return detail::simd_level_slot(); }
// Tests: use `level` from now on in this binary's loops (a plugin keeps its own choice; the
// environment variable reaches every one); capped at what the processor runs; returns the level set.
inline SimdLevel set_simd_level(SimdLevel level) {
  const SimdLevel supported = simd_supported();
  return detail::simd_level_slot() = level < supported ? level : supported;
}

// Runs f() compiled for the level in use (f and everything it calls inlined into that copy).
template <class F> void with_simd(F &&f) {
  switch (simd_level()) {
    case SimdLevel::avx512:
      detail::run_avx512(f);
      return;
    case SimdLevel::avx2:
      detail::run_avx2(f);
      return;
    default:
      detail::run_base(f);
      return;
  }
}
#else
inline SimdLevel simd_supported() { return SimdLevel::base; }
inline SimdLevel simd_level() { return SimdLevel::base; }
inline SimdLevel set_simd_level(SimdLevel) { return SimdLevel::base; }
template <class F> void with_simd(F &&f) { f(); }
#endif

inline const char *simd_name(SimdLevel level) {
  return level == SimdLevel::avx512 ? "avx512" : (level == SimdLevel::avx2 ? "avx2" : "base");
}

}  // namespace spreadmap
