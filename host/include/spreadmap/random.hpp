// Portable random numbers (scene building, surrogate training): std::mt19937_64 is specified bit for bit by the
// standard, but std::*_distribution are not (libstdc++, libc++ and MSVC give different numbers for
// the same seed), so the uniform and normal variates are made here, identically everywhere.
#pragma once
#include <cmath>
#include <cstdint>
#include <random>

namespace spreadmap {

class Random {
 public:
  explicit Random(std::uint64_t seed) : engine_(seed) {}

  // Uniform in [0, 1): the top 53 bits of one 64-bit draw, exactly representable.
  double uniform() { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }
  // Uniform in [lo, hi).
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
  // Standard normal by the Box-Muller transform (one variate per pair of uniforms; the second is
  // discarded so that the stream position never depends on earlier calls).
  double normal() {
    const double u1 = 1.0 - uniform();  // (0, 1]: log(u1) is finite
    const double u2 = uniform();
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(6.283185307179586476925 * u2);
  }
  // An index in [0, n) by the modulus (bias below 2^-40 for the small n it serves); 0 for n = 0.
  std::uint64_t below(std::uint64_t n) { return n ? engine_() % n : 0; }

 private:
  std::mt19937_64 engine_;
};

}  // namespace spreadmap
