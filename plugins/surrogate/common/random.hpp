// Seeded random numbers that are the same on every platform: std::mt19937_64 is fully specified
// by the standard, the distributions are not, so we map its bits to numbers ourselves.
#pragma once
#include <cmath>
#include <cstdint>
#include <random>

namespace spreadmap::surrogate {

class Random {
 public:
  explicit Random(std::uint64_t seed) : engine_(seed) {}
  double uniform() { return double(engine_() >> 11) * 0x1.0p-53; }  // [0, 1)
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
  double normal() {  // Box-Muller; one value per call keeps the stream simple
    const double u1 = 1.0 - uniform(), u2 = uniform();
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(6.283185307179586 * u2);
  }
  std::uint64_t below(std::uint64_t n) { return n ? engine_() % n : 0; }  // bias < 2^-40 for small n

 private:
  std::mt19937_64 engine_;
};

}  // namespace spreadmap::surrogate
