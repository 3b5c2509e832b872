// Size distributions, the portable random numbers and the layer-coverage estimate.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>

#include "powder/coverage.hpp"
#include "spreadmap/random.hpp"
#include "powder/size_distribution.hpp"

namespace sc = spreadmap::powder;

TEST(SceneRandom, UniformIsTheTop53BitsOfTheStandardEngine) {
  // std::mt19937_64's first output for seed 5489 is fixed by the standard's default-seed value.
  spreadmap::Random random(5489);
  EXPECT_EQ(random.uniform(), static_cast<double>(14514284786278117030ull >> 11) * 0x1.0p-53);
}

TEST(SceneRandom, NormalHasZeroMeanUnitVariance) {
  // 200000 draws: standard errors 0.0022 (mean) and 0.0032 (variance); allow 4 of them.
  spreadmap::Random random(3);
  const int n = 200000;
  double sum = 0, sum2 = 0;
  for (int i = 0; i < n; ++i) {
    const double z = random.normal();
    sum += z;
    sum2 += z * z;
  }
  const double mean = sum / n;
  EXPECT_NEAR(mean, 0.0, 4 * 1 / std::sqrt(n));
  EXPECT_NEAR(sum2 / n - mean * mean, 1.0, 4 * std::sqrt(2.0 / n));
}

TEST(SceneDistribution, TruncatedLognormalMeanVolumeMatchesQuadrature) {
  // E[pi d^3/6] from the closed form against a midpoint rule over ln d (1e5 panels: rel. error ~1e-10).
  const double sigma = 0.35, d50 = 30e-6;
  const auto s = sc::SizeDistribution::lognormal(d50, sigma, sc::FractionBasis::number, 18e-6, 60e-6);
  const double a = std::log(18e-6), b = std::log(60e-6);
  const int n = 100000;
  double num = 0, den = 0;
  for (int i = 0; i < n; ++i) {
    const double x = a + (b - a) * (i + 0.5) / n, z = (x - std::log(d50)) / sigma, w = std::exp(-0.5 * z * z);
    num += w * std::exp(3 * x);
    den += w;
  }
  EXPECT_NEAR(s.mean_sphere_volume() / (std::numbers::pi / 6 * num / den), 1.0, 1e-9);
}

TEST(SceneDistribution, VolumeD50IsConvertedToTheNumberMedian) {
  const auto s = sc::SizeDistribution::lognormal(40e-6, 0.4, sc::FractionBasis::volume);
  EXPECT_DOUBLE_EQ(s.number_median(), 40e-6 * std::exp(-3 * 0.16));
}

TEST(SceneDistribution, TableByVolumeGivesExactNumberCounts) {
  // Equal volumes of 200 um and 100 um spheres: number ratio 1 : 8, so 100 and 800 of 900.
  const auto s = sc::SizeDistribution::table({200e-6, 100e-6}, {0.5, 0.5}, sc::FractionBasis::volume);
  spreadmap::Random random(1);
  const auto d = s.sample(900, random);
  ASSERT_EQ(d.size(), 900u);
  EXPECT_EQ(std::count(d.begin(), d.end(), 200e-6), 100);
  EXPECT_EQ(std::count(d.begin(), d.end(), 100e-6), 800);
  // Largest remainder: 10 particles at 1/3 each -> 4, 3, 3.
  const auto thirds = sc::SizeDistribution::table({1e-4, 2e-4, 3e-4}, {1, 1, 1});
  const auto t = thirds.sample(10, random);
  EXPECT_EQ(std::count(t.begin(), t.end(), 1e-4) + std::count(t.begin(), t.end(), 2e-4) +
                std::count(t.begin(), t.end(), 3e-4),
            10);
  EXPECT_EQ(std::count(t.begin(), t.end(), 1e-4), 4);
}

TEST(SceneDistribution, InvalidInputsAreRefused) {
  EXPECT_THROW(sc::SizeDistribution::monodisperse(-1).validate(), sc::PowderError);
  EXPECT_THROW(sc::SizeDistribution::lognormal(1e-4, -0.1).validate(), sc::PowderError);
  EXPECT_THROW(sc::SizeDistribution::lognormal(1e-4, 0.3, sc::FractionBasis::number, 2e-4, 3e-4).validate(),
               sc::PowderError);
  EXPECT_THROW(sc::SizeDistribution::table({1e-4}, {1, 2}).validate(), sc::PowderError);
}

TEST(SceneCoverage, LengthIsVolumeOverPackingThicknessWidth) {
  // 1e-7 m^3 over a 2.5 mm strip at 0.5 mm and packing 0.6: 1e-7 / 7.5e-7 m = 0.1333 m.
  const auto c = sc::sampled_length_check(1e-7, 0.5e-3, 2.5e-3, 0.1);
  EXPECT_NEAR(c.coverable_length, 1e-7 / (0.6 * 0.5e-3 * 2.5e-3), 1e-15);
  EXPECT_TRUE(c.sufficient);
  EXPECT_FALSE(sc::sampled_length_check(1e-7, 0.5e-3, 2.5e-3, 0.2).sufficient);
  EXPECT_THROW(sc::sampled_length_check(1e-7, 0.0, 2.5e-3, 0.1), sc::PowderError);
}
