// A spreader must span a periodic width: the geometry sees no periodic images, so one shorter than the
// width leaves powder unspread and puts a sphere that crosses the seam beside its end face inside it.
// The rule is a closed interval test on the description's y_centre +- length/2 against [lo, hi].
#include <gtest/gtest.h>

#include "workflow/scene/spreader_span.hpp"

namespace sm = spreadmap;

namespace {

sm::sm_spreader_description_v2 spanning(double y_centre, double length) {
  sm::sm_spreader_description_v2 d{};
  d.y_centre = y_centre;
  d.length = length;
  return d;
}

spreadmap::engine::Domain across(double width, bool periodic) {
  spreadmap::engine::Domain d;
  d.hi = {0.12, width, 0.02};
  d.periodic = {false, periodic, false};
  return d;
}

}  // namespace

TEST(SpreaderSpan, TheStudysRollerCentredOnItsWidthSpansItExactly) {
  EXPECT_FALSE(sm::spreader_span_shortfall(spanning(0.035, 0.070), across(0.070, true)));
  EXPECT_FALSE(sm::spreader_span_shortfall(spanning(0.035, 0.070), across(0.070, false)));
}

TEST(SpreaderSpan, ANarrowStripInsideHalfTheDefaultRollerIsSpanned) {
  // the presets' strips: y_centre 0, length 70 mm covers [-35, 35] mm, so any strip [0, W <= 35 mm]
  EXPECT_FALSE(sm::spreader_span_shortfall(spanning(0.0, 0.070), across(0.002, true)));
  EXPECT_FALSE(sm::spreader_span_shortfall(spanning(0.0, 0.070), across(0.035, true)));
  EXPECT_FALSE(sm::spreader_span_shortfall(spanning(0.0, 0.0), across(1.0, true))) << "length 0: unbounded";
}

TEST(SpreaderSpan, HalfOfAPeriodicWidthIsRefusedWithTheCentreAsTheFix) {
  const auto s = sm::spreader_span_shortfall(spanning(0.0, 0.070), across(0.070, true));
  ASSERT_TRUE(s);
  EXPECT_TRUE(s->periodic);
  EXPECT_NE(s->what.find("y = -35..35 mm, the domain 0..70 mm"), std::string::npos) << s->what;
  EXPECT_EQ(s->fix, "set spreader.y_centre: 35 mm (the middle of the width)");
  // just past half the width: short by 1 um
  EXPECT_TRUE(sm::spreader_span_shortfall(spanning(0.0, 0.070), across(0.035001, true)));
}

TEST(SpreaderSpan, AShorterSpreaderThanTheWidthMustGrowToo) {
  const auto s = sm::spreader_span_shortfall(spanning(0.025, 0.050), across(0.070, true));
  ASSERT_TRUE(s);
  EXPECT_EQ(s->fix, "make spreader.length at least 70 mm and set spreader.y_centre: 35 mm");
}

TEST(SpreaderSpan, OpenSidesShortOfTheSpreaderAreAWarningNotARefusal) {
  const auto s = sm::spreader_span_shortfall(spanning(0.0, 0.070), across(0.070, false));
  ASSERT_TRUE(s);
  EXPECT_FALSE(s->periodic);
  EXPECT_NE(s->what.find("never spread"), std::string::npos) << s->what;
}
