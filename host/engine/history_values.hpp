// Tests of a contact's history values that the loops run for every contact out of reach each step.
#pragma once
#include <bit>
#include <cstdint>
#include <type_traits>

namespace spreadmap::engine {

// Whether any of the n values is other than zero (of either sign): one test of their bits, where a
// comparison per value costs a branch or a flag chain each.
template <class Real> bool any_value(const Real *h, unsigned n) {
  using Bits = std::conditional_t<sizeof(Real) == 8, std::uint64_t, std::uint32_t>;
  Bits bits = 0;
  for (unsigned c = 0; c < n; ++c) bits |= std::bit_cast<Bits>(h[c]);
  return Bits(bits << 1) != 0;  // the sign bits shifted out: -0 is zero
}

}  // namespace spreadmap::engine
