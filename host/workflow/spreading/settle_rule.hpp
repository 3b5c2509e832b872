// When a settling run ends: after min_time, once the spheres are at rest, at max_time at the latest.
// "At rest" counts the spheres faster than `speed`: none of them (fraction 1, the fastest sphere
// slower), or at most (1 - fraction) of them, so that a few rattlers bouncing on soft, bouncy contacts
// (a heap of 45-106 um spheres at E = 26 MPa: 99 % of them below 1 mm/s at 0.034 s, the fastest only
// at 0.045 s) do not hold the bed settling to max_time.
#pragma once
#include <cmath>
#include <cstddef>
#include <vector>

namespace spreadmap {

struct SettleRule {
  double min_time = 0, max_time = 0;  // [s]
  double speed = 0;                   // [m/s]
  double fraction = 1;                // of the spheres that must be slower than `speed`, in (0, 1]
};

// Whether spheres of these velocities are still settling by `rule` (time aside).
template <class Real>
bool still_settling(const SettleRule &rule, const std::vector<Real> &vx, const std::vector<Real> &vy,
                    const std::vector<Real> &vz) {
  const std::size_t n = vx.size();
  // the count allowed to move, rounded down (1 - 0.99 is a hair above 0.01: 100 spheres allow 1)
  const auto allowed = static_cast<std::size_t>(std::floor((1 - rule.fraction) * double(n) * (1 + 1e-12)));
  std::size_t moving = 0;
  for (std::size_t i = 0; i < n; ++i)
    moving += std::sqrt(double(vx[i] * vx[i] + vy[i] * vy[i] + vz[i] * vz[i])) > rule.speed ? 1 : 0;
  return moving > allowed;
}

}  // namespace spreadmap
