// Heap insertion: no overlapping pair (brute force), every sphere inside the region and outside the
// exclusions, exact counts, determinism, size statistics, growth and its limit.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "powder/heap.hpp"

namespace sc = spreadmap::powder;

namespace {

constexpr double d = 250e-6;

// The peer scene: roller axis at x = 6 mm, z = 5.5 mm (R = 5 mm), 0.3 mm clearance around it.
sc::HeapSpec peer_like(std::size_t count) {
  sc::HeapSpec s;
  s.region = {{6e-3, 0.0, 0.0}, {18e-3, 2.5e-3, 9.5e-3}};
  s.periodic_y = true;
  s.count = count;
  s.sizes = sc::SizeDistribution::monodisperse(d);
  s.seed = 42;
  s.excluded_cylinders.push_back({6e-3, 5.5e-3, 5.3e-3});
  return s;
}

// Brute force over all pairs: the smallest gap |c_i - c_j| - (r_i + r_j), minimum image along a
// periodic y. Touching (gap 0) is allowed; rounding of the squared distances leaves ~1e-19 m.
double smallest_gap(const sc::Heap &h, bool periodic_y, double width) {
  double worst = 1.0;
  for (std::size_t i = 0; i < h.size(); ++i)
    for (std::size_t j = i + 1; j < h.size(); ++j) {
      double dy = h.y[i] - h.y[j];
      if (periodic_y) dy -= width * std::round(dy / width);
      const double dist = std::sqrt(std::pow(h.x[i] - h.x[j], 2) + dy * dy + std::pow(h.z[i] - h.z[j], 2));
      worst = std::min(worst, dist - h.r[i] - h.r[j]);
    }
  return worst;
}

void expect_inside(const sc::Heap &h, const sc::HeapSpec &s) {
  for (std::size_t i = 0; i < h.size(); ++i) {
    const double r = h.r[i];
    ASSERT_GE(h.x[i] - r, s.region.lo[0]);
    ASSERT_LE(h.x[i] + r, s.region.hi[0]);
    ASSERT_GE(h.z[i] - r, s.region.lo[2]);
    ASSERT_LE(h.z[i] + r, h.top);
    if (s.periodic_y) {
      ASSERT_GE(h.y[i], s.region.lo[1]);
      ASSERT_LT(h.y[i], s.region.hi[1]);
    } else {
      ASSERT_GE(h.y[i] - r, s.region.lo[1]);
      ASSERT_LE(h.y[i] + r, s.region.hi[1]);
    }
    for (const auto &c : s.excluded_cylinders) ASSERT_GE(std::hypot(h.x[i] - c.x, h.z[i] - c.z), c.radius + r);
  }
}

}  // namespace

TEST(SceneHeap, MonodisperseNoOverlapInsideRegionOutsideRoller) {
  const sc::HeapSpec s = peer_like(3000);
  const sc::Heap h = sc::insert_heap(s);
  ASSERT_EQ(h.size(), 3000u);
  EXPECT_DOUBLE_EQ(h.top, 9.5e-3);  // solid fraction ~0.13: no growth needed
  expect_inside(h, s);
  EXPECT_GE(smallest_gap(h, true, 2.5e-3), -1e-18);
  EXPECT_NEAR(h.solid_volume, 3000 * std::numbers::pi / 6 * d * d * d, 1e-20);
}

TEST(SceneHeap, LognormalNoOverlapLargestFirstMedianNearD50) {
  sc::HeapSpec s;
  s.region = {{0.0, 0.0, 0.0}, {10e-3, 4e-3, 8e-3}};
  s.count = 3000;
  const double sigma = 0.3;
  s.sizes = sc::SizeDistribution::lognormal(d, sigma);
  s.seed = 7;
  s.excluded_boxes.push_back({{4e-3, 0.0, 0.0}, {6e-3, 4e-3, 2e-3}});
  s.excluded = [](double x, double, double, double r) { return x + r > 9e-3; };  // a callback too
  const sc::Heap h = sc::insert_heap(s);
  ASSERT_EQ(h.size(), 3000u);
  expect_inside(h, s);
  EXPECT_GE(smallest_gap(h, false, 0.0), -1e-18);
  EXPECT_TRUE(std::is_sorted(h.r.rbegin(), h.r.rend()));  // largest first
  for (std::size_t i = 0; i < h.size(); ++i) {
    EXPECT_LE(h.x[i] + h.r[i], 9e-3);
    const bool in_box = h.x[i] + h.r[i] > 4e-3 && h.x[i] - h.r[i] < 6e-3 && h.z[i] - h.r[i] < 2e-3;
    EXPECT_FALSE(in_box) << i;
    EXPECT_GE(2 * h.r[i], d * std::exp(-3 * sigma) * (1 - 1e-12));  // default truncation
    EXPECT_LE(2 * h.r[i], d * std::exp(3 * sigma) * (1 + 1e-12));
  }
  // Median: the sample median of ln d has standard error sqrt(pi/2) sigma / sqrt(N) = 0.0069;
  // allow 4 of them.
  std::vector<double> lnd;
  for (double r : h.r) lnd.push_back(std::log(2 * r));
  std::nth_element(lnd.begin(), lnd.begin() + lnd.size() / 2, lnd.end());
  EXPECT_NEAR(lnd[lnd.size() / 2], std::log(d), 4 * std::sqrt(std::numbers::pi / 2) * sigma / std::sqrt(3000.0));
}

TEST(SceneHeap, DeterministicForASeed) {
  const sc::Heap a = sc::insert_heap(peer_like(1000)), b = sc::insert_heap(peer_like(1000));
  EXPECT_EQ(a.x, b.x);
  EXPECT_EQ(a.y, b.y);
  EXPECT_EQ(a.z, b.z);
  sc::HeapSpec other = peer_like(1000);
  other.seed = 43;
  EXPECT_NE(sc::insert_heap(other).x, a.x);
}

TEST(SceneHeap, VolumeGivesTheMatchingCount) {
  sc::HeapSpec s = peer_like(0);
  const double v1 = std::numbers::pi / 6 * d * d * d;
  s.solid_volume = 1234.4 * v1;
  EXPECT_EQ(sc::heap_volume_to_count(s.solid_volume, s.sizes), 1234u);
  EXPECT_EQ(sc::insert_heap(s).size(), 1234u);
  s.count = 10;  // both given
  EXPECT_THROW(sc::insert_heap(s), sc::PowderError);
}

TEST(SceneHeap, GrowsUpwardsWhenFullAndFailsWithNumbersAtTheLimit) {
  // 600 spheres in 2 x 2.5 x 1 mm: 0.98 solid fraction if it could not grow, beyond the RSA jamming
  // limit (0.38), so the top must rise (in steps of one diameter).
  sc::HeapSpec s = peer_like(600);
  s.region = {{0.0, 0.0, 0.0}, {2e-3, 2.5e-3, 1e-3}};
  s.excluded_cylinders.clear();
  s.attempts_per_sphere = 2000;
  const sc::Heap h = sc::insert_heap(s);
  ASSERT_EQ(h.size(), 600u);
  EXPECT_GT(h.top, 1e-3);
  const double steps = (h.top - 1e-3) / d;
  EXPECT_NEAR(steps, std::round(steps), 1e-9);
  expect_inside(h, s);
  EXPECT_GE(smallest_gap(h, true, 2.5e-3), -1e-18);

  s.max_top = 1e-3;
  try {
    sc::insert_heap(s);
    FAIL() << "expected PowderError";
  } catch (const sc::PowderError &e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("of 600 spheres"), std::string::npos) << what;
    EXPECT_NE(what.find("max_top"), std::string::npos) << what;
  }
}

TEST(SceneHeap, NarrowPeriodicStripChecksEveryImage) {
  // A strip two diameters wide: fewer than three cells across y, every cell is a neighbour.
  sc::HeapSpec s = peer_like(300);
  s.region = {{0.0, 0.0, 0.0}, {4e-3, 2 * d, 3e-3}};
  s.excluded_cylinders.clear();
  const sc::Heap h = sc::insert_heap(s);
  ASSERT_EQ(h.size(), 300u);
  EXPECT_GE(smallest_gap(h, true, 2 * d), -1e-18);
}

TEST(SceneHeap, RejectsImpossibleRegions) {
  sc::HeapSpec s = peer_like(10);
  s.region.hi[0] = s.region.lo[0] + 0.5 * d;
  EXPECT_THROW(sc::insert_heap(s), sc::PowderError);
}
