// A scene's block wall (workflow/scene/block_wall.hpp): a solid box whose contact is with the nearest
// point of its surface. Closed forms: on a face the overlap is r minus the height above it; beyond an
// edge or a corner the normal points from that edge or corner to the centre and the overlap is r minus
// that distance; a centre inside is pushed out through the nearest face; the block moves only between
// start and stop, and its surface velocity is its velocity then, zero otherwise.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "workflow/scene/block_wall.hpp"

namespace spreadmap::scene {
namespace {

constexpr double inf = std::numeric_limits<double>::infinity();

// A plate 10 mm x 4 mm x 2 mm with its top face at z = 0.
BlockWall plate() { return BlockWall{{0, 0, -2e-3}, {10e-3, 4e-3, 0}, {0, 0, 0}, 0, inf}; }

WallHit<double> hit_at(const BlockWall &b, double x, double y, double z, double r, double t = 0) {
  WallHit<double> hit{0, {0, 0, 0}, {0, 0, 0}};
  EXPECT_TRUE(b(Vec3<double>{x, y, z}, r, t, hit)) << "no contact at " << x << ", " << y << ", " << z;
  return hit;
}

TEST(BlockWall, OnAFaceTheOverlapIsTheRadiusLessTheHeightAboveIt) {
  const double r = 0.5e-3, h = 0.49e-3;
  const auto hit = hit_at(plate(), 3e-3, 2e-3, h, r);
  EXPECT_DOUBLE_EQ(hit.overlap, r - h);
  EXPECT_EQ(hit.normal.x, 0);
  EXPECT_EQ(hit.normal.y, 0);
  EXPECT_EQ(hit.normal.z, 1);
  WallHit<double> none{0, {0, 0, 0}, {0, 0, 0}};
  EXPECT_FALSE(plate()(Vec3<double>{3e-3, 2e-3, 0.51e-3}, r, 0.0, none)) << "apart above the face";
}

TEST(BlockWall, BeyondAnEdgeOrACornerTheNormalPointsFromItToTheCentre) {
  const double r = 0.5e-3, d = 0.3e-3;
  // beyond the edge x = 10 mm, z = 0 along the diagonal of the xz plane
  const auto edge = hit_at(plate(), 10e-3 + d / std::sqrt(2.0), 2e-3, d / std::sqrt(2.0), r);
  EXPECT_NEAR(edge.overlap, r - d, 1e-15);
  EXPECT_NEAR(edge.normal.x, 1 / std::sqrt(2.0), 1e-15);
  EXPECT_NEAR(edge.normal.z, 1 / std::sqrt(2.0), 1e-15);
  EXPECT_EQ(edge.normal.y, 0);
  // beyond the corner (10, 4, 0) mm along (1, 1, 1)
  const double s = d / std::sqrt(3.0);
  const auto corner = hit_at(plate(), 10e-3 + s, 4e-3 + s, s, r);
  EXPECT_NEAR(corner.overlap, r - d, 1e-15);
  for (double c : {corner.normal.x, corner.normal.y, corner.normal.z}) EXPECT_NEAR(c, 1 / std::sqrt(3.0), 1e-14);
}

TEST(BlockWall, AFaceAndItsEdgeMeetWithoutAJump) {
  // A sphere at height h sliding over the edge x = 10 mm: the overlap is r - h on the face and r -
  // sqrt(dx^2 + h^2) beyond it; both equal r - h at the edge. The distance to a convex body changes by
  // no more than the centre moves (no jump at the edge), and the normal turns continuously from +z.
  const double r = 0.5e-3, h = 0.45e-3;
  const double step = 0.5e-6;
  auto last = hit_at(plate(), 10e-3 - 1e-6, 2e-3, h, r);
  for (int k = 1; k <= 40; ++k) {
    const double x = 10e-3 - 1e-6 + k * step;
    const auto hit = hit_at(plate(), x, 2e-3, h, r);
    const double dx = std::max(0.0, x - 10e-3);
    EXPECT_NEAR(hit.overlap, r - std::hypot(dx, h), 1e-15);
    EXPECT_LE(std::fabs(hit.overlap - last.overlap), step * (1 + 1e-9)) << "a jump at x = " << x;
    EXPECT_NEAR(hit.normal.x, dx / std::hypot(dx, h), 1e-12);
    EXPECT_LE(std::fabs(hit.normal.x - last.normal.x), step / h * (1 + 1e-9)) << "the normal jumps at x = " << x;
    last = hit;
  }
}

TEST(BlockWall, ACentreInsideIsPushedOutThroughTheNearestFace) {
  const double r = 0.5e-3;
  // 0.2 mm below the top face, 1.5 mm from the nearest side face: out through the top
  const auto top = hit_at(plate(), 1.5e-3, 2e-3, -0.2e-3, r);
  EXPECT_DOUBLE_EQ(top.overlap, r + 0.2e-3);
  EXPECT_EQ(top.normal.z, 1);
  // 0.1 mm inside the face x = 0, deeper below the top: out through x = 0
  const auto side = hit_at(plate(), 0.1e-3, 2e-3, -1e-3, r);
  EXPECT_DOUBLE_EQ(side.overlap, r + 0.1e-3);
  EXPECT_EQ(side.normal.x, -1);
}

TEST(BlockWall, ItMovesOnlyBetweenStartAndStop) {
  // A piston rising at 10 mm/s from 1 ms to 3 ms: 20 um in all.
  BlockWall piston = plate();
  piston.velocity[2] = 10e-3;
  piston.start = 1e-3;
  piston.stop = 3e-3;
  const double r = 0.5e-3, h = 0.49e-3;
  for (double t : {0.0, 1e-3, 2e-3, 3e-3, 4e-3}) {
    const double rise = 10e-3 * std::clamp(t - 1e-3, 0.0, 2e-3);
    const auto hit = hit_at(piston, 3e-3, 2e-3, h, r, t);
    EXPECT_NEAR(hit.overlap, r - h + rise, 1e-15) << "t = " << t;
    const bool moving = t > 1e-3 && t < 3e-3;
    EXPECT_EQ(hit.velocity.z, moving ? 10e-3 : 0.0) << "t = " << t;
  }
  sm_spreader_pose_v2 pose{};
  piston.pose(5e-3, &pose);
  EXPECT_NEAR(pose.reference[2], -2e-3 + 20e-6, 1e-15);
}

}  // namespace
}  // namespace spreadmap::scene
