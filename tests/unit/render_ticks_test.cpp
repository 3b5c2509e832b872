// Axis ticks and contour levels on any input (issue 37): NaN, infinite or overflowing ranges give no
// ticks, ranges narrower than the spacing of doubles give one, and no count gives more than a bound.
// Before, a range like [1e17, 1e17] or [1e300, next double] looped forever allocating ticks.
#include "host/render/src/canvas2d.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace d = spreadmap::render::detail;

namespace {
constexpr double inf = std::numeric_limits<double>::infinity();
const double not_a_number = std::nan("");
}  // namespace

TEST(RenderTicks, OrdinaryRangesKeepTheirRoundTicks) {
  EXPECT_EQ(d::nice_ticks(0, 10, 5), (std::vector<double>{0, 2, 4, 6, 8, 10}));
  EXPECT_EQ(d::nice_ticks(-1, 1, 4), (std::vector<double>{-1, -0.5, 0, 0.5, 1}));
  EXPECT_EQ(d::nice_ticks(10, 0, 5).size(), 6u) << "reversed bounds";
}

TEST(RenderTicks, NonFiniteRangesGiveNoTicks) {
  for (const auto &[lo, hi] : std::vector<std::pair<double, double>>{
           {not_a_number, 1}, {0, not_a_number}, {not_a_number, not_a_number}, {0, inf}, {-inf, 0}, {-inf, inf}, {-1e308, 1e308}, {inf, inf}}) {
    SCOPED_TRACE(std::to_string(lo) + " .. " + std::to_string(hi));
    EXPECT_TRUE(d::nice_ticks(lo, hi, 6).empty());
  }
}

TEST(RenderTicks, HugeAndDegenerateRangesAreBounded) {
  EXPECT_LE(d::nice_ticks(0, 1e308, 6).size(), 14u);
  EXPECT_GE(d::nice_ticks(0, 1e308, 6).size(), 2u);
  // narrower than the spacing of doubles there: adding the step changes nothing
  EXPECT_EQ(d::nice_ticks(1e17, 1e17, 6).size(), 1u);
  EXPECT_LE(d::nice_ticks(1e300, std::nextafter(1e300, inf), 6).size(), 1u);
  EXPECT_LE(d::nice_ticks(0, 1, 2000000000).size(), 1000u) << "a silly count";
  EXPECT_LE(d::nice_ticks(0, 5e-324, 6).size(), 14u) << "a subnormal span";
}

TEST(RenderTicks, StepMultiplesStopAtTheirBound) {
  EXPECT_EQ(d::step_multiples(-1, 2, 0.5, 10), (std::vector<double>{-0.5, 0, 0.5, 1}));
  EXPECT_EQ(d::step_multiples(0, 1e18, 1, 7).size(), 7u);
  EXPECT_EQ(d::step_multiples(1e17, 1e17 + 1000, 1, 100).size(), 1u) << "no next whole number past 2^53";
  EXPECT_TRUE(d::step_multiples(not_a_number, 1, 1, 10).empty());
  EXPECT_TRUE(d::step_multiples(0, inf, 1, 10).empty());
  EXPECT_TRUE(d::step_multiples(0, 1, 0, 10).empty());
  EXPECT_TRUE(d::step_multiples(0, 1, not_a_number, 10).empty());
}
