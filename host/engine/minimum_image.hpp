// The minimum-image separation of the pair loops and the list build.
#pragma once

namespace spreadmap::engine {

// Minimum image along one axis, the periodicity fixed at compile time and no branch taken: the
// same bits as wrap() (d - L, d - (-L) = d + L, or d - 0 - 0 = d, for -0 too), the shifts selects.
template <bool Periodic, class Real> Real wrap_axis(Real d, Real length) {
  if constexpr (Periodic) {
    const Real h = Real(0.5) * length;
    return (d - (d > h ? length : Real(0))) - (d < -h ? -length : Real(0));
  } else {
    (void)length;
    return d;
  }
}

}  // namespace spreadmap::engine
