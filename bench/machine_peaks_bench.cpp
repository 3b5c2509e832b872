// bench_machine_peaks: what this processor can do, measured rather than quoted, for the limit table
// of docs/performance.md. Per core and for all cores (OpenMP):
//  - the clock, from a chain of dependent integer adds (one cycle each);
//  - floating-point peaks in double and float at 128, 256 and 512-bit width, once with fused
//    multiply-adds (the processor's peak) and once with separate multiplies and adds (what the
//    engine's loops can reach: they are built with -ffp-contract=off for bitwise reproducibility);
//  - the divider's throughput (256-bit double divides and square roots);
//  - read bandwidth from arrays that fit L1, L2, the last level and none of them.
// Prints each figure and the machine. Usage: bench_machine_peaks [--seconds S] (per measurement, 0.3).
#include <immintrin.h>
#include <omp.h>

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

namespace {

using Clock = std::chrono::steady_clock;
double seconds_per_test = 0.3;

std::string cpu_model() {
  std::ifstream in("/proc/cpuinfo");
  for (std::string line; std::getline(in, line);)
    if (line.rfind("model name", 0) == 0) return line.substr(line.find(':') + 2);
  return "unknown processor";
}

// Runs body(reps) with reps doubled from 1 until it takes seconds_per_test; returns (seconds, reps).
// (From 1: one rep of the memory test reads 1 GiB a thread.)
template <class Body> std::pair<double, std::uint64_t> timed(Body body) {
  for (std::uint64_t reps = 1;; reps *= 2) {
    const auto t0 = Clock::now();
    body(reps);
    const double s = std::chrono::duration<double>(Clock::now() - t0).count();
    if (s >= seconds_per_test) return {s, reps};
  }
}

// 8 dependent integer multiplies per turn, 3 cycles each on every x86 core of the last decade (a
// chain of adds would not do: recent cores fold chained immediate adds at rename).
double clock_hz() {
  std::uint64_t sink = 0;
  const auto [s, reps] = timed([&](std::uint64_t n) {
    std::uint64_t a = n | 1;
    const std::uint64_t one = 1;
    for (std::uint64_t i = 0; i < n; ++i) {
      asm volatile("imul %1, %0\n\timul %1, %0\n\timul %1, %0\n\timul %1, %0\n\t"
                   "imul %1, %0\n\timul %1, %0\n\timul %1, %0\n\timul %1, %0"
                   : "+r"(a)
                   : "r"(one));
    }
    sink += a;
  });
  if (sink == 42) std::puts("");
  return 3.0 * 8.0 * double(reps) / s;
}

// 12 independent accumulators hide the latency (4 cycles x up to 2 ports plus slack). Each turn:
// 12 vector FMAs (2 flops a lane) or 12 multiplies + 12 adds (1 flop a lane each).
#define SPREADMAP_PEAK(NAME, TARGET, V, SET1, FMA, MUL, ADD, STORE, LANES, T)                               \
  __attribute__((target(TARGET))) double NAME(std::uint64_t n, bool fused) {                                 \
    V a[12];                                                                                                 \
    for (int k = 0; k < 12; ++k) a[k] = SET1(T(1) + T(k) * T(1e-3));                                         \
    const V m = SET1(T(0.999999)), c = SET1(T(1e-7));                                                        \
    if (fused) {                                                                                             \
      for (std::uint64_t i = 0; i < n; ++i)                                                                  \
        _Pragma("GCC unroll 12") for (int k = 0; k < 12; ++k) a[k] = FMA(a[k], m, c);                       \
    } else {                                                                                                 \
      for (std::uint64_t i = 0; i < n; ++i)                                                                  \
        _Pragma("GCC unroll 12") for (int k = 0; k < 12; ++k) a[k] = ADD(MUL(a[k], m), c);                  \
    }                                                                                                        \
    T out[LANES], sum = 0;                                                                                   \
    for (int k = 0; k < 12; ++k) {                                                                           \
      STORE(out, a[k]);                                                                                      \
      for (int l = 0; l < LANES; ++l) sum += out[l];                                                         \
    }                                                                                                        \
    return double(sum);                                                                                      \
  }

SPREADMAP_PEAK(peak_sse_d, "fma", __m128d, _mm_set1_pd, _mm_fmadd_pd, _mm_mul_pd, _mm_add_pd, _mm_storeu_pd, 2, double)
SPREADMAP_PEAK(peak_sse_f, "fma", __m128, _mm_set1_ps, _mm_fmadd_ps, _mm_mul_ps, _mm_add_ps, _mm_storeu_ps, 4, float)
SPREADMAP_PEAK(peak_avx_d, "avx2,fma", __m256d, _mm256_set1_pd, _mm256_fmadd_pd, _mm256_mul_pd, _mm256_add_pd,
               _mm256_storeu_pd, 4, double)
SPREADMAP_PEAK(peak_avx_f, "avx2,fma", __m256, _mm256_set1_ps, _mm256_fmadd_ps, _mm256_mul_ps, _mm256_add_ps,
               _mm256_storeu_ps, 8, float)
SPREADMAP_PEAK(peak_avx512_d, "avx512f", __m512d, _mm512_set1_pd, _mm512_fmadd_pd, _mm512_mul_pd, _mm512_add_pd,
               _mm512_storeu_pd, 8, double)
SPREADMAP_PEAK(peak_avx512_f, "avx512f", __m512, _mm512_set1_ps, _mm512_fmadd_ps, _mm512_mul_ps, _mm512_add_ps,
               _mm512_storeu_ps, 16, float)

// Divisions and square roots (256-bit double): the pair loop's 1/distance, slip direction and
// reduced mass and radius go through the divider, which is far slower than the multipliers.
__attribute__((target("avx2"))) double divider_avx_d(std::uint64_t n, bool square_root) {
  __m256d a[12];
  for (int k = 0; k < 12; ++k) a[k] = _mm256_set1_pd(1.5 + k * 1e-3);
  const __m256d c = _mm256_set1_pd(2.0);
  if (square_root) {
    for (std::uint64_t i = 0; i < n; ++i)
#pragma GCC unroll 12
      for (int k = 0; k < 12; ++k) a[k] = _mm256_sqrt_pd(a[k]);
  } else {
    for (std::uint64_t i = 0; i < n; ++i)
#pragma GCC unroll 12
      for (int k = 0; k < 12; ++k) a[k] = _mm256_div_pd(c, a[k]);
  }
  double out[4], sum = 0;
  for (auto &v : a) {
    _mm256_storeu_pd(out, v);
    sum += out[0] + out[1] + out[2] + out[3];
  }
  return sum;
}

// Cycles per 256-bit instruction (one core) of the divider.
double divider_cycles(bool square_root, double hz) {
  double sink = 0;
  const auto [s, reps] = timed([&](std::uint64_t n) { sink += divider_avx_d(n, square_root); });
  if (sink == 42) std::puts("");
  return s * hz / (double(reps) * 12.0);
}

using PeakFn = double (*)(std::uint64_t, bool);

// Flops per second of one kernel on `threads` threads (each its own accumulators).
double flops(PeakFn f, int lanes, bool fused, int threads) {
  double sink = 0;
  const auto [s, reps] = timed([&](std::uint64_t n) {
#pragma omp parallel num_threads(threads) reduction(+ : sink)
    sink += f(n, fused);
  });
  if (sink == 42) std::puts("");
  return double(threads) * double(reps) * 12.0 * lanes * 2.0 / s;  // an FMA, or a multiply and an add: 2 flops
}

// Sums n doubles with 8 independent 256-bit accumulators (two loads a cycle at most).
__attribute__((target("avx2"))) double sum_avx2(const double *p, std::size_t n) {
  __m256d acc[8];
  for (auto &a : acc) a = _mm256_setzero_pd();
  for (std::size_t i = 0; i + 32 <= n; i += 32)
#pragma GCC unroll 8
    for (int k = 0; k < 8; ++k) acc[k] = _mm256_add_pd(acc[k], _mm256_loadu_pd(p + i + 4 * k));
  double out[4], sum = 0;
  for (auto &a : acc) {
    _mm256_storeu_pd(out, a);
    sum += out[0] + out[1] + out[2] + out[3];
  }
  return sum;
}

// Read bandwidth (bytes/s) over an array of `bytes` per thread.
double read_bandwidth(std::size_t bytes, int threads) {
  const std::size_t n = bytes / sizeof(double);
  std::vector<std::vector<double>> data(threads);
#pragma omp parallel num_threads(threads)
  data[omp_get_thread_num()].assign(n, 1.0);  // first touch by its reader
  double sink = 0;
  const auto [s, reps] = timed([&](std::uint64_t turns) {
#pragma omp parallel num_threads(threads) reduction(+ : sink)
    {
      const double *p = data[omp_get_thread_num()].data();
      for (std::uint64_t t = 0; t < turns; ++t) {
        sink += sum_avx2(p, n);
        asm volatile("" ::: "memory");
      }
    }
  });
  if (sink == 42) std::puts("");
  return double(threads) * double(reps) * double(n * sizeof(double)) / s;
}

}  // namespace

int main(int argc, char **argv) {
  for (int i = 1; i + 1 < argc; ++i)
    if (std::strcmp(argv[i], "--seconds") == 0) seconds_per_test = std::atof(argv[i + 1]);
  const int cores = int(std::thread::hardware_concurrency());
  __builtin_cpu_init();
  std::printf("machine: %s, %d hardware threads\n", cpu_model().c_str(), cores);
  const double hz = clock_hz();
  std::printf("clock (dependent integer multiplies, one core): %.2f GHz\n\n", hz / 1e9);

  struct Kernel {
    const char *name;
    PeakFn f;
    int lanes;
    const char *feature;
    bool supported;
  };
  const bool fma = __builtin_cpu_supports("fma"), avx2 = fma && __builtin_cpu_supports("avx2"),
             avx512 = __builtin_cpu_supports("avx512f");
  const Kernel kernels[] = {{"128-bit double", peak_sse_d, 2, "fma", fma},
                            {"128-bit float", peak_sse_f, 4, "fma", fma},
                            {"256-bit double", peak_avx_d, 4, "avx2", avx2},
                            {"256-bit float", peak_avx_f, 8, "avx2", avx2},
                            {"512-bit double", peak_avx512_d, 8, "avx512f", avx512},
                            {"512-bit float", peak_avx512_f, 16, "avx512f", avx512}};
  std::printf("%-16s %14s %14s %14s %14s\n", "peak flops", "FMA 1 core", "flops/cycle", "mul+add 1 core",
              (std::to_string(cores) + " cores mul+add").c_str());
  for (const auto &k : kernels) {
    if (!k.supported) {
      std::printf("%-16s (this processor has no %s)\n", k.name, k.feature);
      continue;
    }
    const double fused = flops(k.f, k.lanes, true, 1), split = flops(k.f, k.lanes, false, 1);
    const double all = flops(k.f, k.lanes, false, cores);
    std::printf("%-16s %11.1f GF %11.1f    %11.1f GF %11.1f GF\n", k.name, fused / 1e9, fused / hz, split / 1e9,
                all / 1e9);
  }

  if (__builtin_cpu_supports("avx2"))
    std::printf("\n256-bit double divide: %.1f cycles each (4 lanes); square root: %.1f cycles each\n",
                divider_cycles(false, hz), divider_cycles(true, hz));

  std::printf("\n%-22s %16s %16s\n", "read bandwidth", "1 core", (std::to_string(cores) + " cores").c_str());
  const std::pair<const char *, std::size_t> sizes[] = {
      {"16 KiB (L1)", 16u << 10}, {"1 MiB (L2)", 1u << 20}, {"32 MiB (last level)", 32u << 20}, {"1 GiB (memory)", 1u << 30}};
  for (const auto &[label, bytes] : sizes)
    std::printf("%-22s %13.1f GB/s %13.1f GB/s\n", label, read_bandwidth(bytes, 1) / 1e9,
                read_bandwidth(bytes, cores) / 1e9);
  return 0;
}
