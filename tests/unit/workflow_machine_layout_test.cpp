// The machine of scene.machine as blocks (workflow/spreading/machine_layout.hpp): the blocks tile the
// floor along x from behind the feed to the lip with no gap and no overlap, their tops are the plates
// (z = 0), the piston (-depth + k x dosing x thickness) and the platform (-k x thickness), and the
// strokes move the piston and the platform from layer k - 1's places to layer k's at stroke_speed.
#include <gtest/gtest.h>

#include <limits>

#include "workflow/spreading/machine_layout.hpp"

namespace spreadmap {
namespace {

Scene machine_scene() {
  Scene s;
  s.domain = {30e-3, 1.25e-3, 12e-3, false, true};
  s.powder.distribution = "mono";
  s.powder.diameter = 250e-6;
  s.layers = {10, 500e-6};
  Machine m;
  m.reservoir_from = 6e-3;
  m.reservoir_length = 5e-3;
  m.reservoir_depth = 11e-3;
  m.plate_length = 1e-3;
  m.well_length = 10e-3;
  m.lip_length = 1e-3;
  m.dosing = 2;
  m.stroke_speed = 20e-3;
  m.layer = 3;
  s.machine = m;
  return s;
}

TEST(MachineLayout, BlocksTileTheFloorWithTheirTopsAtTheLayersPlaces) {
  const Scene s = machine_scene();
  const auto walls = machine_walls(s, false);
  ASSERT_EQ(walls.size(), 5u);
  const double tops[] = {0, -11e-3 + 3 * 2 * 500e-6, 0, -3 * 500e-6, 0};
  const double ends[] = {6e-3, 11e-3, 12e-3, 22e-3, 23e-3};
  for (std::size_t i = 0; i < walls.size(); ++i) {
    const auto b = scene::block_of(walls[i]);
    EXPECT_EQ(walls[i].kind, scene::WallKind::block);
    EXPECT_DOUBLE_EQ(b.hi[2], tops[i]) << walls[i].name;
    EXPECT_DOUBLE_EQ(b.hi[0], ends[i]) << walls[i].name;
    if (i > 0) {
      EXPECT_EQ(b.lo[0], scene::block_of(walls[i - 1]).hi[0]) << "a gap or an overlap before " << walls[i].name;
    }
    EXPECT_LE(b.lo[1], 0.0);
    EXPECT_GE(b.hi[1], s.domain.width) << "a block must span the periodic strip";
    EXPECT_LT(b.lo[2], machine_layout(s).bottom) << "a block must reach below the domain";
    EXPECT_EQ(b.max_surface_speed(), 0.0) << "at rest";
  }
  // the domain's bottom lies below the deepest floor (the piston at its start) by two spheres
  EXPECT_DOUBLE_EQ(machine_layout(s).bottom, -(11e-3 + 2 * 250e-6));
}

TEST(MachineLayout, StrokesMoveThePistonAndThePlatformFromTheLayerBeforeAtStrokeSpeed) {
  const Scene s = machine_scene();  // layer 3
  const auto walls = machine_walls(s, true);
  const auto piston = scene::block_of(walls[1]), platform = scene::block_of(walls[3]);
  EXPECT_DOUBLE_EQ(piston.hi[2], -11e-3 + 2 * 2 * 500e-6);  // layer 2's place
  EXPECT_DOUBLE_EQ(platform.hi[2], -2 * 500e-6);
  EXPECT_DOUBLE_EQ(piston.velocity[2], 20e-3);
  EXPECT_DOUBLE_EQ(platform.velocity[2], -20e-3);
  EXPECT_DOUBLE_EQ(piston.stop, 2 * 500e-6 / 20e-3);  // 1 mm at 20 mm/s
  EXPECT_DOUBLE_EQ(platform.stop, 500e-6 / 20e-3);    // 0.5 mm
  EXPECT_DOUBLE_EQ(stroke_time(s), piston.stop);
  // where they stop: layer 3's places
  sm_spreader_pose_v2 pose{};
  piston.pose(1.0, &pose);
  EXPECT_NEAR(pose.reference[2] + (piston.hi[2] - piston.lo[2]), -11e-3 + 3 * 2 * 500e-6, 1e-15);
  platform.pose(1.0, &pose);
  EXPECT_NEAR(pose.reference[2] + (platform.hi[2] - platform.lo[2]), -3 * 500e-6, 1e-15);
  for (std::size_t i : {0u, 2u, 4u}) EXPECT_EQ(scene::block_of(walls[i]).max_surface_speed(), 0.0) << "plates never move";
}

TEST(MachineLayout, TheBuriedPowderSleepsBelowTheFreshLayerBySleepDepth) {
  Scene s = machine_scene();
  EXPECT_EQ(sleep_below(s), -std::numeric_limits<double>::infinity()) << "sleep_depth 0: none by depth";
  s.machine->sleep_depth = 1e-3;
  EXPECT_DOUBLE_EQ(sleep_below(s), -(500e-6 + 1e-3));  // the plates less one layer, less the depth
  s.machine.reset();
  EXPECT_EQ(sleep_below(s), -std::numeric_limits<double>::infinity()) << "no machine: none by depth";
}

}  // namespace
}  // namespace spreadmap
