// spreader/mesh: a box from an STL file is the sharp-edged blade (same overlap, normal and surface
// velocity everywhere), a turning part's surface moves as a rigid body does, its description and pose
// follow from the file and the input, and a wrong unit or a changed file is refused.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <random>

#include "plugins/spreader/blade/blade.hpp"
#include "plugins/spreader/mesh/mesh.hpp"
#include "plugins/spreader/mesh/stl_files.hpp"
#include "unit/spreader_values.hpp"

#include <spreadmap/digest.hpp>

namespace fs = std::filesystem;
namespace sm = spreadmap;
using sm::spreader::Blade;
using sm::spreader::Mesh;
using V = sm::Vec3<double>;
using sm::mesh::testing::Folder;

namespace {


Mesh bind_mesh(const nlohmann::json &overrides) { return sm::test::bind_with<Mesh>(overrides); }

std::string refusal(const nlohmann::json &overrides) {
  try {
    bind_mesh(overrides);
  } catch (const sm::ParamError &e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(MeshSpreader, ABoxFromAnStlFileIsTheSharpEdgedBlade) {
  Folder f("spreadmap_mesh_spreader");
  sm::mesh::testing::write_binary(f.file("blade.stl"), sm::mesh::testing::box({0, -35, 0}, {2, 35, 10}));
  // the blade's defaults: 1 mm thick, 10 mm high, 70 mm long, gap 0.5 mm, start 6 mm, U 0.1 m/s
  const Blade blade = sm::test::bind_with<Blade>({{"thickness", 2e-3}});
  const Mesh mesh = bind_mesh({{"file", f.file("blade.stl")}, {"unit", "mm"}, {"axis_x", 1e-3}});
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> x(3e-3, 11e-3), y(-36e-3, 36e-3), z(0, 12e-3);
  const double r = 0.4e-3;
  int touching = 0;
  for (int k = 0; k < 20000; ++k) {
    const double t = k % 3 == 0 ? -0.01 : 0.02 * (k % 7);
    const V p{x(rng), y(rng), z(rng)};
    sm::WallHit<double> a{}, b{};
    const bool on_blade = blade(p, r, t, a) && a.overlap < r;  // the mesh sees a centre outside the part
    if (!on_blade) continue;
    ++touching;
    ASSERT_TRUE(mesh(p, r, t, b)) << p.x << " " << p.y << " " << p.z << " t " << t;
    EXPECT_NEAR(b.overlap, a.overlap, 1e-15);
    EXPECT_NEAR(b.normal.x, a.normal.x, 1e-12);
    EXPECT_NEAR(b.normal.y, a.normal.y, 1e-12);
    EXPECT_NEAR(b.normal.z, a.normal.z, 1e-12);
    EXPECT_EQ(b.velocity.x, a.velocity.x);
  }
  EXPECT_GT(touching, 200);
  sm::sm_spreader_description_v2 d{};
  mesh.describe(&d);
  EXPECT_EQ(d.vertices, 4u);
  EXPECT_NEAR(d.length, 70e-3, 1e-15);
  EXPECT_NEAR(d.gap, 0.5e-3, 1e-15);
  EXPECT_EQ(d.turns, 0);
  sm::sm_spreader_pose_v2 pose{};
  mesh.pose(0.1, &pose);
  EXPECT_NEAR(pose.x_min, 6e-3 + 0.1 * 0.1 - 1e-3, 1e-15);
  EXPECT_NEAR(pose.x_max, 6e-3 + 0.1 * 0.1 + 1e-3, 1e-15);
}

TEST(MeshSpreader, ATurningPartsSurfaceMovesAsARigidBody) {
  Folder f("spreadmap_mesh_spreader");
  sm::mesh::testing::write_ascii(f.file("square.stl"), sm::mesh::testing::box({-2, -5, -2}, {2, 5, 2}));
  const double omega = -30, U = 0.05, gap = 0.3e-3, start = 4e-3, r = 0.2e-3, depth = 0.05e-3;
  const Mesh m = bind_mesh({{"file", f.file("square.stl")},
                            {"unit", "mm"},
                            {"omega", omega},
                            {"U", U},
                            {"gap", gap},
                            {"start", start},
                            {"y_centre", 1e-3}});
  for (double t : {0.0, 0.01, 0.037, 0.2}) {
    const double angle = omega * t, c = std::cos(angle), s = std::sin(angle);
    // a sphere under the middle of the bottom face (body frame: (0.7 mm, 0, -2 mm - r + depth))
    const double bx = 0.7e-3, bz = -2e-3 - r + depth;
    const V axis{start + U * t, 1e-3, gap + 2e-3};
    const V p{axis.x + c * bx + s * bz, 1.5e-3, axis.z - s * bx + c * bz};
    sm::WallHit<double> hit{};
    ASSERT_TRUE(m(p, r, t, hit)) << t;
    EXPECT_NEAR(hit.overlap, depth, 1e-15);
    EXPECT_NEAR(hit.normal.x, -s, 1e-12);  // R(angle) (0, 0, -1)
    EXPECT_NEAR(hit.normal.z, -c, 1e-12);
    const double ax = c * bx + s * -2e-3, az = -s * bx + c * -2e-3;  // the contact point about the axis
    EXPECT_NEAR(hit.velocity.x, U + omega * az, 1e-12);
    EXPECT_NEAR(hit.velocity.z, -omega * ax, 1e-12);
    sm::sm_spreader_pose_v2 pose{};
    m.pose(t, &pose);
    EXPECT_NEAR(pose.angle, angle, 1e-15);
    EXPECT_NEAR(pose.reference[2], gap + 2e-3, 1e-15);
  }
  EXPECT_NEAR(m.max_surface_speed(), U + 30 * std::sqrt(8.0) * 1e-3, 1e-12);
}

TEST(MeshSpreader, AWrongUnitAMissingUnitOrAChangedFileIsRefused) {
  Folder f("spreadmap_mesh_spreader");
  sm::mesh::testing::write_binary(f.file("blade.stl"), sm::mesh::testing::box({0, -35, 0}, {2, 35, 10}));
  const std::string metres = refusal({{"file", f.file("blade.stl")}, {"unit", "m"}});
  EXPECT_NE(metres.find("the part is 70 m across with unit: m, implausible for a recoater (0.1 mm to 1 m)"), std::string::npos)
      << metres;
  EXPECT_NE(metres.find("set unit: to the one it was exported in"), std::string::npos);
  const std::string microns = refusal({{"file", f.file("blade.stl")}, {"unit", "um"}});
  EXPECT_NE(microns.find("the part is 7e-05 m across with unit: um"), std::string::npos) << microns;
  EXPECT_NE(refusal({{"file", f.file("blade.stl")}, {"unit", ""}}).find("unit: give the STL's length unit"),
            std::string::npos);
  std::ifstream in(f.file("blade.stl"), std::ios::binary);
  const std::string bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  EXPECT_EQ(refusal({{"file", f.file("blade.stl")}, {"unit", "mm"}, {"file_digest", sm::content_digest(bytes)}}),
            "");
  const std::string changed = refusal({{"file", f.file("blade.stl")}, {"unit", "mm"}, {"file_digest", "0"}});
  EXPECT_NE(changed.find("changed since its scene was validated"), std::string::npos) << changed;
  sm::mesh::testing::write_binary(f.file("outline.stl"), {{0, 0, 0, 2, 0, 0, 2, 0, 10}, {0, 0, 0, 2, 0, 10, 0, 0, 10}});
  const std::string flat = refusal({{"file", f.file("outline.stl")}, {"unit", "mm"}});
  EXPECT_NE(flat.find("outline.stl: the part has no extent along y"), std::string::npos) << flat;
  auto holed = sm::mesh::testing::box({0, -35, 0}, {2, 35, 10});
  holed.pop_back();  // one triangle of a face missing
  sm::mesh::testing::write_binary(f.file("holed.stl"), holed);
  const std::string open = refusal({{"file", f.file("holed.stl")}, {"unit", "mm"}});
  EXPECT_NE(open.find("holed.stl: the part is not closed: 3 edge(s) do not join exactly two triangles"),
            std::string::npos)
      << open;
  const std::string gone = refusal({{"file", f.file("gone.stl")}, {"unit", "mm"}});
  EXPECT_NE(gone.find("gone.stl: cannot be opened"), std::string::npos) << gone;
}
