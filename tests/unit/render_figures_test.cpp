// Each figure renders headless (DISPLAY unset: the library starts its own Xvfb) from a small fixed
// input into a PNG of exactly the requested size that is not blank, carries the colours it must
// (colour map ends, both contour families of the map), and matches a stored reference image.
#include "render_fixtures.hpp"
#include "render_image_check.hpp"
#include "temporaries.hpp"

#include <gtest/gtest.h>

#include <spreadmap/render/figures.hpp>

#include <cstdlib>
#include <filesystem>
#include <functional>

namespace r = spreadmap::render;
namespace rt = spreadmap::render::testing;
namespace fs = std::filesystem;

namespace {

// Small figures keep the suite fast and the stored references small (about 50 kB each).
constexpr int ref_width = 640, ref_height = 400;

// Mean absolute difference per channel (0..255). Measured with Debian 12's Mesa llvmpipe: a fresh
// rendering differs from its reference by 0.000; a reframed camera (snapshot of a longer strip) by
// 14.6; the map without its dashed std lines by 1.05. 1.5 leaves room for small rasteriser or font
// differences on another machine while any camera or colour-map change fails; thin missing layers
// are caught by the colour-presence checks instead (they cover too few pixels to move the mean).
constexpr double reference_tolerance = 1.5;

class HeadlessEnvironment : public ::testing::Environment {
 public:
  void SetUp() override { ::unsetenv("DISPLAY"); }  // prove the private Xvfb path
};
const auto* const headless = ::testing::AddGlobalTestEnvironment(new HeadlessEnvironment);

fs::path out_dir() {
  const fs::path d = fs::path(SPREADMAP_BINARY_DIR) / "test_output" / "render";
  fs::create_directories(d);
  return d;
}

r::Options small(const std::string& title = "") {
  r::Options o;
  o.width = ref_width;
  o.height = ref_height;
  o.title = title;
  return o;
}

// Size, non-blank, then the reference comparison (or its regeneration).
rt::Image check_figure(const std::string& name, const fs::path& png, std::size_t min_colours) {
  EXPECT_TRUE(fs::exists(png)) << png;
  EXPECT_TRUE(temporaries_beside(png).empty()) << "temporary file left behind";
  const rt::Image im = rt::read_png(png);
  EXPECT_EQ(im.width, ref_width);
  EXPECT_EQ(im.height, ref_height);
  EXPECT_GT(rt::distinct_colours(im), min_colours) << name << " looks blank";
  const fs::path ref = rt::reference_path(name);
  if (rt::regenerate_references()) {
    fs::create_directories(ref.parent_path());
    fs::copy_file(png, ref, fs::copy_options::overwrite_existing);
  } else {
    EXPECT_TRUE(fs::exists(ref)) << "no reference " << ref << "; run once with SPREADMAP_REGENERATE_REFERENCES=1";
    if (fs::exists(ref)) {
      EXPECT_LT(rt::mean_abs_difference(im, rt::read_png(ref)), reference_tolerance)
          << name << " differs from " << ref << " (camera, colour map or layout changed?); inspect " << png
          << " and regenerate with SPREADMAP_REGENERATE_REFERENCES=1 if the change is intended";
    }
  }
  return im;
}

std::array<int, 3> rgb255(double r, double g, double b) {
  return {static_cast<int>(r * 255 + 0.5), static_cast<int>(g * 255 + 0.5), static_cast<int>(b * 255 + 0.5)};
}

}  // namespace

TEST(RenderFigures, SnapshotShowsParticlesRollerAndSpeedBar) {
  const fs::path png = out_dir() / "snapshot.png";
  r::snapshot(rt::heap_snapshot(), png, small("snapshot"));
  const auto im = check_figure("snapshot", png, 200);
  // The roller's stripe/spoke colour (210, 30, 30 lit) is present: the rotation mark is drawn.
  std::size_t reddish = 0;
  for (const auto& p : im.pixels)
    if (p[0] > 120 && p[1] < 60 && p[2] < 60) ++reddish;
  EXPECT_GT(reddish, 100u);
}

TEST(RenderFigures, SnapshotRollerMarkFollowsTheAngle) {
  // Half a turn moves the spoke from the top half of the face to the bottom half: the images differ.
  r::snapshot(rt::heap_snapshot(500, 0.0), out_dir() / "angle_0.png", small());
  r::snapshot(rt::heap_snapshot(500, 3.14159265358979), out_dir() / "angle_pi.png", small());
  EXPECT_GT(rt::mean_abs_difference(rt::read_png(out_dir() / "angle_0.png"), rt::read_png(out_dir() / "angle_pi.png")),
            0.05);
}

TEST(RenderFigures, HeightmapUsesTheWholeColourMap) {
  const fs::path png = out_dir() / "heightmap.png";
  r::heightmap(rt::layer_heightmap(), png, small("height map"));
  const auto im = check_figure("heightmap", png, 100);
  // The lowest and highest cells take the two ends of viridis (flat 2-D colours, no lighting).
  EXPECT_GT(rt::count_colour(im, rgb255(0.267, 0.005, 0.329), 2), 5u);
  EXPECT_GT(rt::count_colour(im, rgb255(0.993, 0.906, 0.144), 2), 5u);
}

TEST(RenderFigures, SurfaceWithTrainingAndTestPoints) {
  const fs::path png = out_dir() / "surface.png";
  r::surface(rt::roughness_surface(), png, small("R_q surface"));
  check_figure("surface", png, 300);
}

TEST(RenderFigures, ParityTwoPanels) {
  const fs::path png = out_dir() / "parity.png";
  r::parity(rt::two_output_parity(), png, small("parity"));
  const auto im = check_figure("parity", png, 50);
  EXPECT_GT(rt::count_colour(im, rgb255(0.12, 0.47, 0.71), 1), 50u);  // training markers
  EXPECT_GT(rt::count_colour(im, rgb255(0.95, 0.45, 0.05), 1), 20u);  // test markers
}

TEST(RenderFigures, ProcessMapHasBothContourFamilies) {
  const fs::path png = out_dir() / "map.png";
  r::process_map(rt::process_map_input(), png, small("process map"));
  const auto im = check_figure("map", png, 100);
  // Filled R_q bands: at least 4 distinct palette colours cover sizeable areas.
  int bands = 0;
  const std::array<std::array<int, 3>, 9> yellow_red{{{255, 255, 204},
                                                      {255, 237, 160},
                                                      {254, 217, 118},
                                                      {254, 178, 76},
                                                      {253, 141, 60},
                                                      {252, 78, 42},
                                                      {227, 26, 28},
                                                      {189, 0, 38},
                                                      {128, 0, 38}}};
  for (const auto& c : yellow_red) bands += rt::count_colour(im, c, 3) > 200 ? 1 : 0;
  EXPECT_GE(bands, 3) << "filled R_q bands missing";
  // V_s lines in their dark blue.
  EXPECT_GT(rt::count_colour(im, rgb255(0.05, 0.1, 0.35), 1), 100u) << "V_s contour lines missing";
  // Frontier and optimum.
  EXPECT_GT(rt::count_colour(im, rgb255(0.0, 0.45, 0.95), 1), 50u) << "efficient frontier missing";
  EXPECT_GT(rt::count_colour(im, rgb255(0.2, 0.95, 0.3), 1), 20u) << "optimum marker missing";
}

TEST(RenderFigures, TradeoffIsLogLogWithBothErrorsAndTheScatter) {
  // Four fidelities over two decades of cost; errors from 0.1 % to 20 %: two decades too.
  r::TradeoffInput in;
  in.points = {{"reference", 40, 0, 0, true},
               {"stiff", 25, -1.2, 2.0, false},
               {"quick", 12, 0.3, -0.6, false},
               {"soft", 1.5, 8.0, 20.0, false}};
  in.vs_scatter = 1.5;
  in.rq_scatter = 3.0;
  const fs::path png = out_dir() / "tradeoff.png";
  r::tradeoff(in, png, small("trade"));
  const auto im = check_figure("tradeoff", png, 50);
  // Markers and the dashed scatter lines of both series, in their colours.
  EXPECT_GT(rt::count_colour(im, rgb255(0.12, 0.47, 0.71), 1), 150u) << "V_s markers or scatter line missing";
  EXPECT_GT(rt::count_colour(im, rgb255(0.84, 0.15, 0.16), 1), 150u) << "R_q markers or scatter line missing";
  r::TradeoffInput bad = in;
  bad.points[1].cost = 0;  // no log of zero cost
  EXPECT_THROW(r::tradeoff(bad, out_dir() / "bad_tradeoff.png", small()), r::RenderError);
}

TEST(RenderFigures, ReferenceComparisonCatchesAChangedCamera) {
  // The comparison sees a missing layer (map without its std lines: 1.05 measured, > 0.3 required)
  // and fails a reframed camera (snapshot of a longer strip: 14.6 measured, > tolerance required).
  if (rt::regenerate_references()) GTEST_SKIP() << "references being regenerated";
  r::process_map(rt::process_map_input(false), out_dir() / "map_no_std.png", small("process map"));
  EXPECT_GT(
      rt::mean_abs_difference(rt::read_png(out_dir() / "map_no_std.png"), rt::read_png(rt::reference_path("map"))),
      0.3);
  r::Options wide = small("snapshot");
  auto moved = rt::heap_snapshot();
  moved.domain.hi[0] = 0.05;  // longer strip: the automatic camera frames it differently
  r::snapshot(moved, out_dir() / "snapshot_moved.png", wide);
  EXPECT_GT(rt::mean_abs_difference(rt::read_png(out_dir() / "snapshot_moved.png"),
                                    rt::read_png(rt::reference_path("snapshot"))),
            reference_tolerance);
}

TEST(RenderFigures, AnimationWritesNumberedFrames) {
  std::vector<r::SnapshotInput> frames;
  for (int i = 0; i < 3; ++i) frames.push_back(rt::heap_snapshot(300, 0.5 * i));
  const auto files = r::animation_frames(frames, out_dir() / "frames", "heap", small());
  ASSERT_EQ(files.size(), 3u);
  EXPECT_EQ(files[2].filename(), "heap_0002.png");
  for (const auto& f : files) EXPECT_EQ(rt::read_png(f).width, ref_width);
}

TEST(RenderFigures, VectorCopyWhenGl2psIsAvailable) {
  if (!r::vector_output_available()) GTEST_SKIP() << "VTK built without gl2ps";
  r::Options o = small("parity");
  o.vector_format = "svg";
  r::parity(rt::two_output_parity(), out_dir() / "parity_vector.png", o);
  EXPECT_TRUE(fs::exists(out_dir() / "parity_vector.svg"));
  EXPECT_GT(fs::file_size(out_dir() / "parity_vector.svg"), 1000u);
  EXPECT_TRUE(temporaries_beside(out_dir() / "parity_vector.svg").empty());
}

TEST(RenderFigures, BadInputsAreRefusedWithASentence) {
  r::SnapshotInput bad = rt::heap_snapshot(10);
  bad.speed.pop_back();
  EXPECT_THROW(r::snapshot(bad, out_dir() / "bad.png", small()), r::RenderError);
  r::HeightmapInput h;
  h.nx = 2;
  h.ny = 2;
  h.height = {1, 2, 3};
  EXPECT_THROW(r::heightmap(h, out_dir() / "bad.png", small()), r::RenderError);
  EXPECT_FALSE(fs::exists(out_dir() / "bad.png"));
}
