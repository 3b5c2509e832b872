// The angle fits of calibration on surfaces of known slope: a cone of spheres (angle of repose) and
// a tilted bed (drum). The top sphere of each column touches the exact surface, so the fitted angle
// is the set one up to the binning (a constant offset of the heights: no bias on the slope).
#include <gtest/gtest.h>

#include <cmath>

#include "spreadmap/random.hpp"
#include "workflow/calibrate/angle_fit.hpp"

namespace {

using spreadmap::engine::ParticleSet;
constexpr double pi = 3.14159265358979323846;

void add(ParticleSet &s, double x, double y, double z, double r) {
  s.x.push_back(x), s.y.push_back(y), s.z.push_back(z), s.radius.push_back(r);
}

// Columns of spheres (radius r, on a square grid of pitch 2r) under the cone h = H - tan(angle) rho
// over a plate at z = base; `jitter` moves each top sphere up or down by up to jitter * r.
ParticleSet cone(double angle_deg, double base, double jitter, std::uint64_t seed) {
  const double r = 0.5e-3, height = 20e-3, reach = height / std::tan(angle_deg * pi / 180);
  spreadmap::Random random(seed);
  ParticleSet s;
  for (double x = -reach; x <= reach; x += 2 * r)
    for (double y = -reach; y <= reach; y += 2 * r) {
      const double top = height - std::tan(angle_deg * pi / 180) * std::hypot(x, y);
      if (top < 2 * r) continue;
      add(s, x, y, base + top - r + jitter * r * random.uniform(-1, 1), r);  // the surface sphere
      add(s, x, y, base + r, r);                                             // one on the plate
    }
  return s;
}

TEST(CalibrateAngleFit, ConeOfKnownAngleIsMeasuredWithinAQuarterDegree) {
  for (double angle : {22.0, 30.0, 38.0}) {
    const auto fit = spreadmap::calibrate::heap_angle(cone(angle, 1e-3, 0, 1), 1e-3);
    EXPECT_NEAR(fit.angle_deg, angle, 0.25) << angle;
    EXPECT_EQ(fit.parts_deg.size(), 8u);
    EXPECT_LT(fit.spread_deg, 1.0) << angle;
  }
}

TEST(CalibrateAngleFit, RoughConeKeepsItsAngleAndReportsAnUncertainty) {
  const auto fit = spreadmap::calibrate::heap_angle(cone(30, 0, 0.6, 7), 0, 12);
  EXPECT_NEAR(fit.angle_deg, 30, 1.0);
  EXPECT_GT(fit.uncertainty_deg, 0);
  EXPECT_NEAR(fit.uncertainty_deg, fit.spread_deg / std::sqrt(12.0), 1e-12);
  // Three standard errors cover the truth (a rough check that the uncertainty is not far too small).
  EXPECT_LT(std::abs(fit.angle_deg - 30), 3 * fit.uncertainty_deg + 0.25);
}

TEST(CalibrateAngleFit, TiltedDrumBedIsMeasuredFromItsMiddle) {
  const double r = 0.5e-3, radius = 25e-3, slope = std::tan(33 * pi / 180);
  ParticleSet s;
  for (double x = -radius; x <= radius; x += 2 * r)
    for (double y = 0; y < 10e-3; y += 2 * r) {
      const double top = -slope * x;  // the free surface through the axis
      const double floor = -std::sqrt(std::max(0.0, radius * radius - x * x));
      // The curled ends at the wall: the surface bends over near |x| = R; the fit must ignore them.
      const double curl = std::abs(x) > 0.85 * radius ? 4e-3 : 0;
      if (top - curl - r > floor) add(s, x, y, top - curl - r, r), add(s, x, y, floor + r, r);
    }
  const auto fit = spreadmap::calibrate::bed_angle(s, 4);
  EXPECT_NEAR(fit.angle_deg, 33, 0.25);
  EXPECT_EQ(fit.parts_deg.size(), 4u);
}

TEST(CalibrateAngleFit, FlatLayerIsNoHeapAndSaysWhy) {
  ParticleSet s;
  for (int i = 0; i < 40; ++i) add(s, i * 1e-3, 0, 0.5e-3, 0.5e-3);
  try {
    spreadmap::calibrate::heap_angle(s, 0);
    FAIL() << "a single flat row has no flank";
  } catch (const std::runtime_error &e) {
    EXPECT_NE(std::string(e.what()).find("40 particles"), std::string::npos) << e.what();
  }
}

}  // namespace
