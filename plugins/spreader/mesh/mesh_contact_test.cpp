// A triangle mesh as a wall, against closed forms and the engine's analytic plane: a sphere resting on
// a meshed plate feels the plane's force; one rolling across the plate's shared edges and corners
// follows the plane's trajectory (no jump, nothing counted twice); an impact on a corner rebounds
// with the law's restitution; the inside of a closed part is told from the outside; and a sphere far
// from a mesh costs no triangle test, whatever the mesh's size.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <random>

#include "plugins/spreader/mesh/stl_files.hpp"
#include "unit/engine_test_law.hpp"

#include <spreadmap/mesh/triangle_mesh.hpp>

namespace sm = spreadmap;
using namespace sm::engine;
using namespace sm::engine::testing;
using sm::mesh::TriangleMesh;
using sm::mesh::testing::Facet;
using V = sm::Vec3<double>;

namespace {

std::vector<sm::mesh::Triangle> metres(const std::vector<Facet> &facets, double scale = 1e-3) {
  std::vector<sm::mesh::Triangle> out;
  for (const Facet &f : facets) {
    sm::mesh::Triangle t;
    for (int k = 0; k < 9; ++k) t.corner[k / 3][k % 3] = double(f[k]) * scale;
    out.push_back(t);
  }
  return out;
}

// A resting mesh as a geometry: the nearest surface point, no motion.
struct FixedMesh {
  std::shared_ptr<const TriangleMesh> surface;
  template <class Real> bool operator()(const sm::Vec3<Real> &p, Real r, Real, sm::WallHit<Real> &hit) const {
    sm::mesh::SurfacePoint near;
    if (!surface->nearest({double(p.x), double(p.y), double(p.z)}, double(r), near)) return false;
    hit.overlap = Real(double(r) - near.distance);
    hit.normal = {Real(near.normal.x), Real(near.normal.y), Real(near.normal.z)};
    hit.velocity = {0, 0, 0};
    return hit.overlap > 0;
  }
  double max_surface_speed() const { return 0; }
  void describe(sm::sm_spreader_description_v2 *) const {}
  void pose(double, sm::sm_spreader_pose_v2 *) const {}
};

Settings quiet(std::array<double, 3> gravity, double dt) {
  Settings s;
  s.log = [](const std::string &) {};
  s.gravity = gravity;
  s.dt = dt;
  return s;
}

constexpr double r = 0.5e-3, density = 2500;
const Domain box_domain{{-0.01, -0.01, -0.01}, {0.02, 0.02, 0.02}, {false, false, false}};

// One sphere against either the mesh (as a geometry) or the analytic plane z = 0 (as a plane wall).
struct OneSphere {
  TestSpringDashpot law;
  std::unique_ptr<Simulation<double>> sim;
  FixedMesh mesh;
  OneSphere(const TestSpringDashpot &l, const ParticleSet &p, std::array<double, 3> gravity,
            std::shared_ptr<const TriangleMesh> surface, double dt = 2e-6)
      : law(l), mesh{std::move(surface)} {
    sim = std::make_unique<Simulation<double>>(box_domain, bind(law), quiet(gravity, dt));
    if (mesh.surface) sim->add_geometry({&sm::detail::GeometryOps<FixedMesh>::table, &mesh, bind(law), "mesh"});
    else sim->add_plane_wall({{0, 0, 0}, {0, 0, 1}, {0, 0, 0}, bind(law), true, "plane"});
    sim->add_particles(p, density);
  }
};

ParticleSet sphere_at(double x, double y, double z, double vx = 0, double vy = 0, double vz = 0) {
  ParticleSet p;
  push_particle(p, x, y, z, r, vx, vy, vz);
  return p;
}

}  // namespace

TEST(MeshContact, ASphereRestingOnAMeshedPlateFeelsTheAnalyticPlanesForce) {
  const auto plate = std::make_shared<const TriangleMesh>(metres(sm::mesh::testing::plate(8, 1.0f)));
  const auto law = TestSpringDashpot::with_restitution(1e3, 1.0);
  const double delta = 2e-6, dt = 1e-8;  // a step so short that the sphere stays where it was put
  // a face's interior, an edge (a diagonal), a corner shared by six triangles
  for (const auto &xy : {std::array<double, 2>{3.3e-3, 4.6e-3}, {2.5e-3, 2.5e-3}, {4e-3, 4e-3}}) {
    OneSphere on_mesh(law, sphere_at(xy[0], xy[1], r - delta), {0, 0, 0}, plate, dt);
    OneSphere on_plane(law, sphere_at(xy[0], xy[1], r - delta), {0, 0, 0}, nullptr, dt);
    on_mesh.sim->step();
    on_plane.sim->step();
    const double f = on_plane.sim->arrays().fz[0];
    EXPECT_NEAR(f, 1e3 * delta, 1e-6 * 1e3 * delta) << "the spring's force k delta";
    EXPECT_NEAR(on_mesh.sim->arrays().fz[0], f, 1e-12 * f) << xy[0] << ", " << xy[1];
    EXPECT_EQ(on_mesh.sim->arrays().fx[0], 0.0);
    EXPECT_EQ(on_mesh.sim->arrays().fy[0], 0.0);
  }
}

TEST(MeshContact, RollingAcrossSharedEdgesAndCornersFollowsThePlaneWithNoJump) {
  const auto plate = std::make_shared<const TriangleMesh>(metres(sm::mesh::testing::plate(8, 1.0f)));
  const auto law = TestSpringDashpot::with_restitution(1e3, 0.3, 0.4);  // friction: it rolls
  // a resting depth under gravity, then obliquely across edges, diagonals and corners
  const double settle = sphere_mass(r, density) * 9.81 / 1e3;
  OneSphere on_mesh(law, sphere_at(0.6e-3, 1.1e-3, r - settle, 0.05, 0.031), {0, 0, -9.81}, plate);
  OneSphere on_plane(law, sphere_at(0.6e-3, 1.1e-3, r - settle, 0.05, 0.031), {0, 0, -9.81}, nullptr);
  double worst = 0, largest_step_mesh = 0, largest_step_plane = 0, f_mesh = 0, f_plane = 0;
  for (int s = 0; s < 80000; ++s) {
    on_mesh.sim->step();
    on_plane.sim->step();
    const double fm = on_mesh.sim->arrays().fz[0], fp = on_plane.sim->arrays().fz[0];
    worst = std::max(worst, std::fabs(fm - fp));
    if (s > 0) {
      largest_step_mesh = std::max(largest_step_mesh, std::fabs(fm - f_mesh));
      largest_step_plane = std::max(largest_step_plane, std::fabs(fp - f_plane));
    }
    f_mesh = fm, f_plane = fp;
  }
  const auto &m = on_mesh.sim->arrays(), &p = on_plane.sim->arrays();
  EXPECT_GT(m.x[0], 5e-3) << "it crossed several squares";
  EXPECT_GT(m.y[0], 4e-3);
  const double weight = sphere_mass(r, density) * 9.81;
  EXPECT_LT(worst, 1e-9 * weight) << "the mesh's normal force is the plane's at every step";
  EXPECT_LE(largest_step_mesh, largest_step_plane + 1e-9 * weight) << "no jump at an edge or corner";
  EXPECT_NEAR(m.x[0], p.x[0], 1e-12);
  EXPECT_NEAR(m.y[0], p.y[0], 1e-12);
  EXPECT_NEAR(m.wy[0], p.wy[0], 1e-9 * std::fabs(p.wy[0]));
}

TEST(MeshContact, AnImpactOnACornerReboundsWithTheLawsRestitution) {
  const auto tip = std::make_shared<const TriangleMesh>(metres(sm::mesh::testing::pyramid(1.0f, 2.0f)));
  for (double e : {0.3, 0.7, 0.95}) {
    const auto law = TestSpringDashpot::with_restitution(1e3, e);
    const double v0 = 0.2, h = 2e-3;
    OneSphere on_tip(law, sphere_at(0, 0, h + r + 20e-6, 0, 0, -v0), {0, 0, 0}, tip);
    while (on_tip.sim->time() < 2e-3) on_tip.sim->step();
    EXPECT_NEAR(on_tip.sim->arrays().vz[0] / v0, e, 2e-3 * e) << "the law's restitution";
    EXPECT_EQ(on_tip.sim->arrays().vx[0], 0.0) << "a corner's normal points at the centre";
    EXPECT_GT(on_tip.sim->arrays().z[0], h + r) << "it left the corner";
  }
}

TEST(MeshContact, InsideAClosedPartTheNormalPointsOutAndTheDistanceIsNegative) {
  const TriangleMesh part(metres(sm::mesh::testing::box({0, 0, 0}, {2, 4, 1})));
  sm::mesh::SurfacePoint near;
  ASSERT_TRUE(part.nearest({1.0e-3, 2.0e-3, 0.9e-3}, 0.5e-3, near));  // 0.1 mm under the top face
  EXPECT_NEAR(near.distance, -0.1e-3, 1e-15);
  EXPECT_EQ(near.normal.z, 1.0);
  ASSERT_TRUE(part.nearest({2.3e-3, 2.0e-3, 1.4e-3}, 0.6e-3, near));  // beside the top edge at x = 2 mm
  EXPECT_NEAR(near.distance, 0.5e-3, 1e-15);
  EXPECT_NEAR(near.normal.x, 0.6, 1e-12);
  EXPECT_NEAR(near.normal.z, 0.8, 1e-12);
  ASSERT_TRUE(part.nearest({1.95e-3, 3.9e-3, 0.5e-3}, 0.5e-3, near));  // inside, near a vertical edge
  EXPECT_NEAR(near.distance, -0.05e-3, 1e-15);
  EXPECT_NEAR(near.normal.x, 1.0, 1e-12);
  ASSERT_TRUE(part.nearest({-0.3e-3, -0.4e-3, 1.0e-3}, 0.6e-3, near));  // beyond a corner
  EXPECT_NEAR(near.distance, 0.5e-3, 1e-15);
  EXPECT_NEAR(near.normal.y, -0.8, 1e-12);
}

TEST(MeshContact, ACentreDeepInsideAClosedPartIsFoundAndPushedOutThroughTheNearestFace) {
  // a box and a roller (the 256-sided one of bench/mesh_roller) against their closed forms
  const TriangleMesh part(metres(sm::mesh::testing::box({0, 0, 0}, {2, 4, 1})));
  sm::mesh::SurfacePoint near;
  EXPECT_FALSE(part.nearest({1.0e-3, 1.5e-3, 0.6e-3}, 0.1e-3, near)) << "no surface within the radius";
  ASSERT_TRUE(part.contact({1.0e-3, 1.5e-3, 0.6e-3}, 0.1e-3, near));
  EXPECT_NEAR(near.distance, -0.4e-3, 1e-15);
  EXPECT_EQ(near.normal.z, 1.0);
  EXPECT_FALSE(part.contact({1.0e-3, 1.5e-3, 1.6e-3}, 0.1e-3, near)) << "above it, out of reach";
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> x(-0.5e-3, 2.5e-3), y(-0.5e-3, 4.5e-3), z(-0.5e-3, 1.5e-3);
  for (int k = 0; k < 20000; ++k) {
    const V p{x(rng), y(rng), z(rng)};
    const bool in = p.x > 0 && p.x < 2e-3 && p.y > 0 && p.y < 4e-3 && p.z > 0 && p.z < 1e-3;
    ASSERT_EQ(part.inside(p), in) << p.x << " " << p.y << " " << p.z;
  }
  // rays through a shared diagonal (the box's top face), a corner of four faces and an edge between
  // two faces (a pyramid's apex and side edge) are counted once
  const TriangleMesh tip(metres(sm::mesh::testing::pyramid(1.0f, 2.0f)));
  EXPECT_TRUE(part.inside({0.5e-3, 1.0e-3, 0.5e-3})) << "under the top face's diagonal";
  EXPECT_TRUE(tip.inside({0, 0, 0.5e-3})) << "under the apex";
  EXPECT_TRUE(tip.inside({0.3e-3, 0.3e-3, 0.2e-3})) << "under a side edge";
  EXPECT_FALSE(tip.inside({0.9e-3, 0.9e-3, 1.5e-3})) << "beside the apex, outside";
  // an open mesh (a plate) has no inside: a centre far under it touches nothing
  const TriangleMesh plate(metres(sm::mesh::testing::plate(2, 1.0f, 1.0f)));
  EXPECT_TRUE(part.closed());
  EXPECT_FALSE(plate.closed());
  EXPECT_FALSE(plate.inside({1e-3, 1e-3, 0.5e-3}));
  EXPECT_FALSE(plate.contact({1e-3, 1e-3, 0.5e-3}, 0.1e-3, near));
  EXPECT_FALSE(part.contact({std::nan(""), 1e-3, 0.5e-3}, 0.1e-3, near)) << "a NaN centre touches nothing";
}

TEST(MeshContact, ASphereFarFromAMeshCostsNoTriangleTestAndCostDoesNotGrowWithItsSize) {
  const TriangleMesh small(metres(sm::mesh::testing::plate(4, 1.0f))), large(metres(sm::mesh::testing::plate(64, 1.0f)));
  ASSERT_EQ(large.triangles(), 64u * 64u * 2u);
  sm::mesh::SurfacePoint near;
  std::size_t far_small = 0, far_large = 0, near_small = 0, near_large = 0;
  EXPECT_FALSE(small.nearest({1.3e-3, 1.7e-3, 2e-3}, r, near, &far_small));
  EXPECT_FALSE(large.nearest({1.3e-3, 1.7e-3, 2e-3}, r, near, &far_large));
  EXPECT_EQ(far_small, 0u);
  EXPECT_EQ(far_large, 0u);
  EXPECT_TRUE(small.nearest({1.3e-3, 1.7e-3, 0.4e-3}, r, near, &near_small));
  EXPECT_TRUE(large.nearest({1.3e-3, 1.7e-3, 0.4e-3}, r, near, &near_large));
  EXPECT_EQ(near_small, near_large) << "the same cells, whatever lies beyond them";
  EXPECT_LE(near_large, 4u * 18u) << "4 cells, each with the triangles of at most 9 squares";
  EXPECT_NEAR(near.distance, 0.4e-3, 1e-15);
}
