// Units as users write them convert to SI exactly where the decimal arithmetic allows it: the
// result must be the very double that the SI literal gives (EXPECT_EQ, not a tolerance), because the
// value enters the case hash and a 1-ulp difference would make "2.5 um" and "2.5e-6" different cases.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "core/units.hpp"

namespace sm = spreadmap;

namespace {
constexpr double pi = 3.14159265358979323846;
}

TEST(CoreUnits, LengthsWithAndWithoutSpaceAreTheSameSiValue) {
  EXPECT_EQ(sm::parse_in("250 um", "m"), 250e-6);
  EXPECT_EQ(sm::parse_in("250um", "m"), 250e-6);
  EXPECT_EQ(sm::parse_in("0.25 mm", "m"), 250e-6);
  EXPECT_EQ(sm::parse_in("  250 um  ", "m"), 250e-6);
  EXPECT_EQ(sm::parse_in("10 mm", "m"), 0.01);
}

TEST(CoreUnits, DecimalPrefixesGiveTheDoubleOfTheSiLiteral) {
  // 2.5 * 1e-6 is 1 ulp away from 2.5e-6; the conversion must divide by the exact 1e6 instead.
  EXPECT_EQ(sm::parse_in("2.5 um", "m"), 2.5e-6);
  EXPECT_EQ(sm::parse_in("50 um", "m"), 50e-6);
  EXPECT_EQ(sm::parse_in("5 um", "m"), 5e-6);
  EXPECT_EQ(sm::parse_in("0.5 mm", "m"), 0.5e-3);
  EXPECT_EQ(sm::parse_in("1.25 mm", "m"), 1.25e-3);
  EXPECT_EQ(sm::parse_in("7.5e-1 us", "s"), 7.5e-7);
  EXPECT_EQ(sm::parse_in("200 GPa", "Pa"), 200e9);
  EXPECT_EQ(sm::parse_in("3 cm", "m"), 0.03);
  EXPECT_EQ(sm::parse_in("12 nm", "m"), 12e-9);
}

TEST(CoreUnits, CompoundUnitsOfTheIssue) {
  EXPECT_EQ(sm::parse_in("100 mm/s", "m/s"), 0.1);
  EXPECT_EQ(sm::parse_in("40 mm/s", "m/s"), 0.04);
  EXPECT_EQ(sm::parse_in("-20 rad/s", "rad/s"), -20.0);
  EXPECT_EQ(sm::parse_in("4430 kg/m^3", "kg/m^3"), 4430.0);
  EXPECT_EQ(sm::parse_in("4.43 g/cm^3", "kg/m^3"), 4430.0);
  EXPECT_EQ(sm::parse_in("1e-6 s", "s"), 1e-6);
  EXPECT_EQ(sm::parse_in("9.81 m/s^2", "m/s^2"), 9.81);
  EXPECT_EQ(sm::parse_in("4430 kg/m3", "kg/m^3"), 4430.0);  // "m3" means m^3
  EXPECT_EQ(sm::parse_in("2 N/m", "N/m"), 2.0);
}

TEST(CoreUnits, AnglesAndRevolutions) {
  // rad is dimensionless, so rpm is 1/s like rad/s and deg is a plain number
  EXPECT_DOUBLE_EQ(sm::parse_in("60 rpm", "rad/s"), 2 * pi);
  EXPECT_DOUBLE_EQ(sm::parse_in("-30 rpm", "1/s"), -pi);
  EXPECT_DOUBLE_EQ(sm::parse_in("180 deg", "-"), pi);
  EXPECT_DOUBLE_EQ(sm::parse_in("90deg", "rad"), pi / 2);
  EXPECT_EQ(sm::parse_in("2 min", "s"), 120.0);
}

TEST(CoreUnits, BareNumbersAreSi) {
  EXPECT_EQ(sm::parse_in("0.00025", "m"), 0.00025);
  EXPECT_EQ(sm::parse_in("-3", "rad/s"), -3.0);
  EXPECT_EQ(sm::parse_in("4430", "kg/m^3"), 4430.0);
  const auto q = sm::parse_quantity("1e3");
  EXPECT_FALSE(q.has_unit);
  EXPECT_EQ(q.value, 1000.0);
}

TEST(CoreUnits, QuantityReportsItsDimension) {
  const auto q = sm::parse_quantity("100 mm/s");
  ASSERT_TRUE(q.has_unit);
  EXPECT_EQ(q.unit.dim, (sm::Dimension{{1, 0, -1}}));
  EXPECT_EQ(q.unit.dim.str(), "m/s");
  EXPECT_EQ(sm::parse_quantity("1 kg/m^3").unit.dim.str(), "kg/m^3");
  EXPECT_EQ(sm::parse_quantity("1 m/s^2").unit.dim.str(), "m/s^2");
  EXPECT_EQ(sm::parse_quantity("1 rad").unit.dim.str(), "1");
}

TEST(CoreUnits, NanAndInfinityAreRejected) {
  for (const char *text : {"nan", "NaN", ".nan", "nan um", "inf", "-inf", "Infinity m", "1e400", "1e400 m"})
    EXPECT_THROW(sm::parse_in(text, "m"), std::invalid_argument) << text;
}

TEST(CoreUnits, UnknownUnitsAreRejectedWithTheirName) {
  try {
    sm::parse_in("250 furlongs", "m");
    FAIL() << "no error";
  } catch (const std::invalid_argument &e) {
    EXPECT_NE(std::string(e.what()).find("unknown unit 'furlongs'"), std::string::npos) << e.what();
  }
  for (const char *text : {"3 mmm", "1 m/s/s", "2 m^x", "1 kgg/m^3", "5 %%"})
    EXPECT_THROW(sm::parse_in(text, "m"), std::invalid_argument) << text;
  EXPECT_FALSE(sm::parse_unit("parsec").has_value());
}

TEST(CoreUnits, WrongDimensionNamesBothUnits) {
  try {
    sm::parse_in("250 kg", "m");
    FAIL() << "no error";
  } catch (const std::invalid_argument &e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("dimension of kg"), std::string::npos) << what;
    EXPECT_NE(what.find("expected m"), std::string::npos) << what;
  }
  EXPECT_THROW(sm::parse_in("100 mm/s", "m"), std::invalid_argument);
  EXPECT_THROW(sm::parse_in("9.81 m/s^2", "m/s"), std::invalid_argument);
  EXPECT_THROW(sm::parse_in("4430 kg/m^2", "kg/m^3"), std::invalid_argument);
}

TEST(CoreUnits, NotANumberIsRejected) {
  for (const char *text : {"", "   ", "big", "mm", "um 250", "1.2.3 m"})
    EXPECT_THROW(sm::parse_in(text, "m"), std::invalid_argument) << "'" << text << "'";
}
