// The example scenes (examples/scenes/) through the real binary, `spreadmap simulate`, each checked
// against what physics says of it: the rebound height of a dropped sphere (e^2 h), the momentum two
// colliding spheres exchange ((1 + e) m_eq v_rel) and keep in total, the force the contact output
// reports (the law's closed form in the written state), the slope of a heap left by a lifted
// cylinder (within the range such a powder shows) and the layer a roller wall leaves behind it.
// Also: the outputs ParaView opens (states.pvd naming every state file), and bad scenes refused
// before anything runs.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <numbers>
#include <sstream>

#include "workflow/calibrate/angle_fit.hpp"
#include "workflow/process.hpp"

namespace fs = std::filesystem;
namespace t = spreadmap::test;

namespace {

const fs::path examples = fs::path(SPREADMAP_SOURCE_DIR) / "examples" / "scenes";

// A CSV with a header as a list of rows keyed by column name.
std::vector<std::map<std::string, double>> read_csv(const fs::path &file) {
  std::ifstream in(file);
  std::string line;
  std::vector<std::string> names;
  std::vector<std::map<std::string, double>> rows;
  while (std::getline(in, line)) {
    std::stringstream ss(line);
    std::string cell;
    std::vector<std::string> cells;
    while (std::getline(ss, cell, ',')) cells.push_back(cell);
    if (names.empty()) {
      names = cells;
      continue;
    }
    std::map<std::string, double> row;
    for (std::size_t k = 0; k < cells.size() && k < names.size(); ++k) row[names[k]] = std::stod(cells[k]);
    rows.push_back(row);
  }
  return rows;
}

class Scenes : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("spreadmap_powders_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) + "_" +
            std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    if (!HasFailure()) fs::remove_all(dir_);
  }
  // Runs an example scene (or any scene file) into dir_/out; returns the number of outputs it wrote.
  std::size_t simulate(const std::string &scene) { return simulate_file(examples / scene); }
  std::size_t simulate_file(const fs::path &scene) {
    const auto r = t::run({{"simulate", scene.string(), "--out", (dir_ / "out").string()}, {}, {}, {}});
    EXPECT_EQ(r.exit_code, 0) << r.describe();
    std::ifstream in(dir_ / "out" / "summary.json");
    if (!in) return 0;
    return nlohmann::json::parse(in)["outputs"].get<std::size_t>();
  }
  std::vector<std::map<std::string, double>> particles(std::size_t k) {
    char name[32];
    std::snprintf(name, sizeof name, "particles_%04zu.csv", k);
    return read_csv(dir_ / "out" / name);
  }
  fs::path dir_;
};

}  // namespace

TEST_F(Scenes, DropOnPlateReboundsToRestitutionSquaredTimesHeight) {
  // examples/scenes/drop_on_plate.yaml: bottom of the sphere h = 10 mm above the plate, e = 0.8.
  const double h = 10e-3, e = 0.8, radius = 1e-3;
  const std::size_t n = simulate("drop_on_plate.yaml");
  ASSERT_GT(n, 100u);
  std::vector<double> z;
  for (std::size_t k = 0; k < n; ++k) z.push_back(particles(k).at(0).at("z") - radius);
  EXPECT_DOUBLE_EQ(z[0], h);
  // the first impact: the lowest sample; the rebound apex: the highest sample after it
  const std::size_t impact = std::min_element(z.begin(), z.end()) - z.begin();
  ASSERT_LT(impact + 1, z.size());
  const double apex = *std::max_element(z.begin() + impact, z.end());
  // Closed form e^2 h; gravity during the 31 us contact and the step (omega_0 dt = 0.1) are below
  // 1e-3 of it, the sampling of the apex every 0.25 ms below 1e-5.
  std::printf("rebound apex %.6g m, closed form e^2 h = %.6g m (relative difference %.2e)\n", apex, e * e * h,
              apex / (e * e * h) - 1);
  EXPECT_NEAR(apex, e * e * h, 2e-3 * e * e * h);
  // ParaView's entry point lists every state file, in time order
  std::ifstream pvd(dir_ / "out" / "states.pvd");
  std::stringstream text;
  text << pvd.rdbuf();
  EXPECT_NE(text.str().find("state_0000.vtp"), std::string::npos);
  char last[32];
  std::snprintf(last, sizeof last, "state_%04zu.vtp", n - 1);
  EXPECT_NE(text.str().find(last), std::string::npos);
  EXPECT_TRUE(fs::exists(dir_ / "out" / last));
}

TEST_F(Scenes, TwoSpheresExchangeTheClosedFormMomentumAndKeepTheTotal) {
  // examples/scenes/two_spheres.yaml: radii 1 and 1.5 mm, 2500 kg/m^3, +0.5 and -0.2 m/s, e = 0.7
  const double rho = 2500, e = 0.7;
  const double m1 = rho * 4.0 / 3.0 * std::numbers::pi * 1e-9, m2 = rho * 4.0 / 3.0 * std::numbers::pi * 3.375e-9;
  const double v1 = 0.5, v2 = -0.2, m_eq = m1 * m2 / (m1 + m2);
  const std::size_t n = simulate("two_spheres.yaml");
  ASSERT_EQ(n, 5u);
  auto by_id = [](const std::vector<std::map<std::string, double>> &rows, double id) {
    for (const auto &r : rows)
      if (r.at("id") == id) return r;
    ADD_FAILURE() << "no particle with id " << id;
    return rows.front();
  };
  const auto last = particles(n - 1);
  const auto a = by_id(last, 0), b = by_id(last, 1);
  EXPECT_NEAR(a.at("mass"), m1, 1e-12 * m1);
  const double p0 = m1 * v1 + m2 * v2, p1 = a.at("mass") * a.at("vx") + b.at("mass") * b.at("vx");
  const double exchanged = m1 * (a.at("vx") - v1), expected = -(1 + e) * m_eq * (v1 - v2);
  std::printf(
      "momentum: total %.17g -> %.17g kg m/s (error %.2e of |m1 v1| + |m2 v2|); exchanged %.9g, closed form "
      "%.9g (relative %.2e)\n",
      p0, p1, std::fabs(p1 - p0) / (m1 * std::fabs(v1) + m2 * std::fabs(v2)), exchanged, expected,
      exchanged / expected - 1);
  EXPECT_NEAR(p1, p0, 1e-12 * (m1 * std::fabs(v1) + m2 * std::fabs(v2)));
  EXPECT_NEAR(exchanged, expected, 1e-3 * std::fabs(expected));
  EXPECT_NEAR(a.at("vy"), 0, 1e-15);  // head-on: nothing sideways, friction or not
  EXPECT_NEAR(a.at("wz"), 0, 1e-12);

  // Output 1 falls inside the contact: the contact output reports the law's force in that state,
  // F = k delta + c v_approach on sphere 0 along -x (the linear spring-dashpot: k = m_eq V^2 / D^2,
  // c = 2 zeta sqrt(k m_eq), zeta = -ln e / sqrt(pi^2 + ln^2 e); V = 1 m/s, D = 10 um).
  const auto during = particles(1);
  const auto contacts = read_csv(dir_ / "out" / "contacts_0001.csv");
  ASSERT_EQ(contacts.size(), 1u);
  const auto pa = by_id(during, 0), pb = by_id(during, 1);
  const double delta = pa.at("radius") + pb.at("radius") - (pb.at("x") - pa.at("x"));
  EXPECT_NEAR(contacts[0].at("overlap"), delta, 1e-12 * delta);
  ASSERT_GT(delta, 0);
  const double k = m_eq * 1.0 / (10e-6 * 10e-6), le = std::log(e);
  const double c = 2 * (-le / std::sqrt(std::numbers::pi * std::numbers::pi + le * le)) * std::sqrt(k * m_eq);
  const double approach = pa.at("vx") - pb.at("vx"), force = k * delta + c * approach;
  const double on_first = contacts[0].at("id_i") == 0 ? contacts[0].at("fx") : -contacts[0].at("fx");
  EXPECT_NEAR(on_first, -force, 1e-9 * force);
  EXPECT_EQ(read_csv(dir_ / "out" / "contacts_0004.csv").size(), 0u);  // apart again
}

TEST_F(Scenes, LiftedCylinderLeavesAHeapAtItsAngleOfRepose) {
  // examples/scenes/angle_of_repose.yaml: 1500 spheres of 2 mm, friction 0.5, rolling friction 0.1.
  const std::size_t n = simulate("angle_of_repose.yaml");
  ASSERT_EQ(n, 12u);
  const auto rows = particles(n - 1);
  ASSERT_GT(rows.size(), 1400u);  // a few may roll off the plate, out of the domain
  // The angle as calibration measures it (workflow/calibrate/angle_fit.hpp), per quarter of the heap.
  spreadmap::engine::ParticleSet state;
  for (const auto &r : rows) {
    state.x.push_back(r.at("x")), state.y.push_back(r.at("y")), state.z.push_back(r.at("z"));
    state.radius.push_back(r.at("radius"));
  }
  const auto fit = spreadmap::calibrate::heap_angle(state, 0.0, 4);
  const double angle = fit.angle_deg;
  const std::vector<double> &quarters = fit.parts_deg;
  std::printf("angle of repose %.2f deg (+- %.2f deg); quarters %.2f %.2f %.2f %.2f deg\n", angle, fit.uncertainty_deg,
              quarters[0], quarters[1], quarters[2], quarters[3]);
  // 17.8 degrees with this scene (seed 7); over five seeds the same fit scatters by 0.4 degrees
  // (docs/calibration.md). The range is a regression bound around it, not an external reference; a
  // heap of frictionless or freely rolling spheres spreads flat (about 6 degrees).
  EXPECT_GT(angle, 15);
  EXPECT_LT(angle, 25);
  // a cone all around: every quarter stands (16.8-18.3 degrees with this seed)
  for (double q : quarters) {
    EXPECT_GT(q, 8);
    EXPECT_LT(q, 30);
  }
}

TEST_F(Scenes, ARollerWallSpreadsALayerNoThickerThanItsGap) {
  // examples/scenes/roller_spreading.yaml: 400 spheres of d = 200 um, a roller wall of R = 1 mm at a
  // gap of 300 um travelling from x = 2 mm to 14 mm; the spreading scene a workflow's case builds.
  const double d = 200e-6, gap = 300e-6, trailing_edge = 13e-3;
  const std::size_t n = simulate("roller_spreading.yaml");
  ASSERT_EQ(n, 10u);
  const auto rows = particles(n - 1);
  std::ifstream in(dir_ / "out" / "summary.json");
  const auto removed = nlohmann::json::parse(in)["removed"].get<std::size_t>();
  EXPECT_EQ(rows.size() + removed, 400u);  // every sphere is in the domain or counted as having left it
  double top = 0, solid = 0;
  std::size_t behind = 0, ahead = 0;
  for (const auto &r : rows) {
    const double x = r.at("x"), radius = r.at("radius");
    if (x > trailing_edge) ++ahead;
    if (x < 3e-3 || x > trailing_edge) continue;
    ++behind;
    top = std::max(top, r.at("z") + radius);
    if (x > 4e-3 && x < 12e-3) solid += 4.0 / 3.0 * std::numbers::pi * radius * radius * radius;
  }
  const double thickness = solid / (8e-3 * 1e-3);  // solid volume over the strip's area from 4 to 12 mm
  std::printf(
      "behind the roller: %zu spheres, highest top %.1f um (gap %.0f um), solid thickness %.1f um; %zu "
      "pushed ahead, %zu left the domain\n",
      behind, top * 1e6, gap * 1e6, thickness * 1e6, ahead, removed);
  // Nothing passes the roller above its gap (a sphere resting a fraction of a diameter higher, on
  // others it was squeezed between, is all there is room for) ...
  EXPECT_GT(top, d);
  EXPECT_LT(top, gap + 0.25 * d);
  // ... the layer holds less solid than the gap filled at random close packing (0.64), and
  // something: it is a layer (0.35 of the gap measured), not a bare plate ...
  EXPECT_LT(thickness, 0.64 * gap);
  EXPECT_GT(thickness, 0.2 * gap);
  // ... and the roller pushes the rest of the heap ahead of it.
  EXPECT_GT(ahead, 20u);
}

TEST_F(Scenes, AFixedMeshWallHoldsPowderOutOfItsPart) {
  // examples/scenes/mesh_ridge.yaml: 300 spheres of d = 200 um poured onto a 45-degree roof (ridge.stl,
  // a spreader wall that never travels) centred at x = 5 mm, 4 mm wide, 2 mm high. At the end every
  // sphere is outside the roof: its centre at least r - overlap_max(4 um) from both faces.
  const std::size_t n = simulate("mesh_ridge.yaml");
  ASSERT_EQ(n, 4u);
  const auto rows = particles(n - 1);
  std::ifstream in(dir_ / "out" / "summary.json");
  EXPECT_EQ(rows.size() + nlohmann::json::parse(in)["removed"].get<std::size_t>(), 300u);
  double deepest = 0;  // how far a sphere reaches into the roof [m]
  std::size_t on_faces = 0;
  for (const auto &r : rows) {
    const double u = r.at("x") - 5e-3, z = r.at("z"), radius = r.at("radius");
    // signed distance of the centre to the roof's faces z = 2 mm - |u| (each face's outward normal
    // is (+-1, 0, 1)/sqrt 2), where the centre lies over the roof
    if (std::fabs(u) > 2e-3) continue;
    const double distance = (z - (2e-3 - std::fabs(u))) / std::numbers::sqrt2;
    deepest = std::max(deepest, radius - distance);
    if (distance < radius + 10e-6) ++on_faces;
  }
  std::printf("%zu spheres touch the roof's faces; the deepest reaches %.2f um into it\n", on_faces,
              deepest * 1e6);
  EXPECT_LT(deepest, 4e-6) << "no deeper than the law's largest overlap";
  EXPECT_GT(on_faces, 5u) << "spheres rest on the faces, piled between the ridge and the end walls";
}

namespace {

// A scene around a particle file `csv` (two 1 mm spheres by default) and extra YAML lines.
struct BadScene {
  std::string csv = "x,y,z,radius,density\n0,0,0.002,0.001,2500\n0.003,0,0.002,0.001,2500\n";
  std::string walls = "walls:\n  - {type: plane, point: [0, 0, 0], normal: [0, 0, 1]}\n";
  std::string extra;
  std::string domain = "domain: {lo: [-10 mm, -10 mm, -1 mm], hi: [10 mm, 10 mm, 20 mm]}\n";
};

}  // namespace

class BadScenes : public Scenes {
 protected:
  // Validates the scene; it must be refused (exit 2) naming `where` and saying `what`.
  void refused(const BadScene &s, const std::string &where, const std::string &what) {
    std::ofstream(dir_ / "p.csv") << s.csv;
    std::ofstream(dir_ / "s.yaml") << "version: 1\nname: bad\n"
                                   << s.domain
                                   << "contact: {use: hooke_slider}\n"
                                      "particles: {file: p.csv}\n"
                                   << s.walls << "run: {duration: 1 ms}\n"
                                   << s.extra;
    const auto v = t::run({{"validate", (dir_ / "s.yaml").string()}, {}, {}, {}});
    EXPECT_EQ(v.exit_code, 2) << v.describe();
    EXPECT_NE(v.err.find(where), std::string::npos) << "not named: " << where << "\n" << v.err;
    EXPECT_NE(v.err.find(what), std::string::npos) << "not said: " << what << "\n" << v.err;
    EXPECT_EQ(t::crash_marker(v.err), "") << v.err;
    const auto r = t::run({{"simulate", (dir_ / "s.yaml").string(), "--out", (dir_ / "out").string()}, {}, {}, {}});
    EXPECT_EQ(r.exit_code, 2) << r.describe();
    EXPECT_FALSE(fs::exists(dir_ / "out")) << "it ran";
  }
};

TEST_F(BadScenes, AreRefusedBeforeAnythingRunsWithTheFileLineOrKey) {
  const std::string csv = (dir_ / "p.csv").string(), yaml = (dir_ / "s.yaml").string();
  struct BadFile {
    std::string csv, where, what;
  };
  const std::string head = "x,y,z,radius,density\n", good = "0,0,0.002,0.001,2500\n";
  for (const BadFile &f :
       std::vector<BadFile>{{"x,y,radius,density\n0,0,0.001,2500\n", ":1:1", "no 'z' column"},
                            {head + good + "0.003,0,nan,0.001,2500\n", ":3:", "not a finite number"},
                            {head + "0,0,0.002,-0.001,2500\n", ":2:", "a radius must be > 0"},
                            {head + "0,0,0.002,0.001,-2500\n", ":2:", "a density must be > 0"},
                            {head + good + "0.0015,0,0.002,0.001,2500\n", ":2: particle 0", "overlaps particle 1"},
                            {head + good + "0.003,0,-0.0005,0.001,2500\n", ":3: particle 1", "wrong side of wall"},
                            {head + good + "0.05,0,0.002,0.001,2500\n", ":3: particle 1", "outside the domain"}}) {
    BadScene s;
    s.csv = f.csv;
    refused(s, csv + f.where, f.what);
  }
  BadScene s;
  s.walls = "walls:\n  - {type: plane, point: [0, 0, 0], normal: [0, 0, 0]}\n";
  refused(s, yaml + ":7:", "walls[0].normal: the direction has zero length");
  s.walls = "walls:\n  - {type: plane, point: [0, 0, 0], normal: [0, 0, 1], frction: 0.3}\n";
  refused(s, "walls[0].frction", "did you mean 'friction'");
  s.walls = "";
  s.extra = "gravty: off\n";
  refused(s, yaml + ":7:1: gravty", "did you mean 'gravity'");
  s.extra = "gravity: [0, 0, -9.81 m/s]\n";
  refused(s, "gravity[2]", "m/s^2");
  s.extra = "";
  // spreader walls: the plugin named and checked by its own schema, no geometry keys of other walls
  s.walls = "walls:\n  - {type: spreader}\n";
  refused(s, yaml + ":7:", "walls[0].spreader: required value missing");
  s.walls = "walls:\n  - {type: spreader, spreader: {use: rollr}}\n";
  refused(s, "walls[0].spreader.use", "roller");
  s.walls = "walls:\n  - {type: spreader, spreader: {use: roller, gap: -1 mm}}\n";
  refused(s, "walls[0].spreader.gap", "outside [0, 0.1] m");
  s.walls = "walls:\n  - {type: spreader, normal: [0, 0, 1], spreader: {use: blade}}\n";
  refused(s, "walls[0].normal", "not a key of a spreader wall");
  // blocks: two corners with room between them, a motion that stops after it starts, no keys of other walls
  s.walls = "walls:\n  - {type: block, lo: [0, 0, -1 mm], hi: [1 mm, 1 mm, -1 mm]}\n";
  refused(s, "walls[0].hi", "hi.z is not above lo.z: the block is empty");
  s.walls = "walls:\n  - {type: block, lo: [-5 mm, -5 mm, -1 mm], hi: [5 mm, 5 mm, 0], velocity: [0, 0, 1 mm/s], "
            "start: 2 ms, stop: 1 ms}\n";
  refused(s, "walls[0].stop", "stop (0.001 s) is not after start (0.002 s)");
  s.walls = "walls:\n  - {type: block, lo: [-5 mm, -5 mm, -1 mm], hi: [5 mm, 5 mm, 0], open_top: true}\n";
  refused(s, "walls[0].open_top", "not a key of a block wall");
  s.walls = "walls:\n  - {type: block, lo: [-5 mm, -5 mm, -1 mm], hi: [5 mm, 5 mm, 2.5 mm]}\n";
  refused(s, ":2: particle 0", "wrong side of wall 'walls[0] (block)'");
  s.walls = "walls:\n  - {type: spreader, spreader: {use: roller}, stop: 1 s}\n";
  refused(s, "walls[0].stop", "not a key of a spreader wall");
  // a roller 10 mm long across a periodic 20 mm: the seam beside its end face would put spheres inside it
  s.domain = "domain: {lo: [-10 mm, -10 mm, -1 mm], hi: [10 mm, 10 mm, 20 mm], periodic: [y]}\n";
  s.walls = "walls:\n  - {type: spreader, spreader: {use: roller, length: 10 mm}}\n";
  refused(s, "walls[0].spreader.y_centre", "make spreader.length at least 20 mm and set spreader.y_centre: 0 mm");
}

// A scene written by the test: the YAML after `version: 1` and the particle CSV.
class WrittenScenes : public Scenes {
 protected:
  std::size_t simulate_written(const std::string &yaml, const std::string &csv) {
    std::ofstream(dir_ / "p.csv") << csv;
    std::ofstream(dir_ / "s.yaml") << "version: 1\n" << yaml;
    return simulate_file(dir_ / "s.yaml");
  }
  // The highest z of particle `id` after its lowest sample.
  double apex_after_impact(std::size_t outputs, double id) {
    std::vector<double> z;
    for (std::size_t k = 0; k < outputs; ++k)
      for (const auto &row : particles(k))
        if (row.at("id") == id) z.push_back(row.at("z"));
    const std::size_t impact = std::min_element(z.begin(), z.end()) - z.begin();
    return *std::max_element(z.begin() + impact, z.end());
  }
};

TEST_F(WrittenScenes, ASphereReboundsFromAFixedSphereAsFromAnImmovableBody) {
  // A sphere dropped from h = 5 mm (gap) onto a fixed sphere of the same size straight below: the
  // fixed one stays exactly where it is, and it weighs as an immovable body, so the rebound reaches
  // e^2 h as on a wall (with the real mass of the fixed sphere it would rebound differently).
  const double h = 5e-3, e = 0.6;
  const std::size_t n = simulate_written(
      "name: fixed\ndomain: {lo: [-5 mm, -5 mm, -5 mm], hi: [5 mm, 5 mm, 20 mm]}\n"
      "contact: {use: hooke_slider, v_max: 1 m/s, overlap_max: 10 um, restitution: 0.6, friction: 0}\n"
      "particles: {file: p.csv, density: 2500 kg/m^3}\n"
      "run: {duration: 0.06 s, dt: 0.1 us, output_every: 0.25 ms}\n",
      "x,y,z,radius,fixed,id\n0,0,0,0.001,1,0\n0,0,0.007,0.001,0,1\n");
  ASSERT_GT(n, 200u);
  const auto last = particles(n - 1);
  for (const auto &row : last)
    if (row.at("id") == 0) {
      EXPECT_EQ(row.at("z"), 0.0);
      EXPECT_EQ(row.at("vz"), 0.0);
      EXPECT_EQ(row.at("fixed"), 1.0);
      EXPECT_NEAR(row.at("mass"), 2500 * 4.0 / 3.0 * std::numbers::pi * 1e-9, 1e-20);
    }
  const double apex = apex_after_impact(n, 1) - 0.002;  // gap between the spheres at the apex
  std::printf("rebound from a fixed sphere: %.6g m, closed form e^2 h = %.6g m (relative %.2e)\n", apex, e * e * h,
              apex / (e * e * h) - 1);
  EXPECT_NEAR(apex, e * e * h, 2e-3 * e * e * h);
}

TEST_F(WrittenScenes, ASphereInsideATubeReboundsWithTheRestitutionAndATurningTubeDragsIt) {
  // No gravity. Sphere 0 moves radially at 0.3 m/s against the inside of a tube along z of radius
  // 5 mm: it comes back with e times its speed. Sphere 1 hits the wall of a second, turning tube
  // (omega about +z) and is dragged along its surface by friction.
  const double e = 0.7;
  const std::size_t n = simulate_written(
      "name: tube\ngravity: off\ndomain: {lo: [-20 mm, -10 mm, -10 mm], hi: [20 mm, 10 mm, 10 mm]}\n"
      "contact: {use: hooke_slider, v_max: 1 m/s, overlap_max: 10 um, restitution: 0.7, friction: 0.3}\n"
      "particles: {file: p.csv, density: 2500 kg/m^3}\n"
      "walls:\n"
      "  - {type: cylinder, base: [-10 mm, 0, -5 mm], radius: 5 mm, height: 10 mm, friction: 0}\n"
      "  - {type: cylinder, base: [10 mm, 0, -5 mm], radius: 5 mm, height: 10 mm, omega: 20 rad/s}\n"
      "run: {duration: 30 ms, dt: 0.1 us, output_every: 5 ms}\n",
      "x,y,z,vx,radius,id\n-0.01,0,0,0.3,0.001,0\n0.0135,0,0,0.1,0.001,1\n");
  ASSERT_EQ(n, 7u);
  const auto last = particles(n - 1);
  for (const auto &row : last) {
    if (row.at("id") == 0) {
      const double speed = std::hypot(row.at("vx"), row.at("vy"));
      std::printf("tube rebound speed %.9g m/s, closed form %.9g m/s\n", speed, e * 0.3);
      EXPECT_NEAR(speed, e * 0.3, 1e-3 * e * 0.3);
      EXPECT_LT(row.at("vx"), 0);  // it came back
    } else {
      // the turning surface moves along +y at x = +R from the axis: friction drags the sphere that way
      EXPECT_GT(row.at("vy"), 1e-3) << "not dragged by the turning tube";
    }
  }
}

TEST_F(WrittenScenes, BlocksMakeAStepThatReboundsWithTheRestitutionAndAPistonThatLiftsByItsTravel) {
  // Sphere 0 slides (no friction) along a block floor into a block standing on it (a step, a concave
  // corner): it keeps resting on the floor and comes back with e times its speed. Sphere 1 rests on a
  // piston block that rises at 10 mm/s from 10 ms to 20 ms: it ends 100 um higher.
  const double e = 0.7;
  const std::size_t n = simulate_written(
      "name: blocks\ndomain: {lo: [-20 mm, -10 mm, -10 mm], hi: [20 mm, 10 mm, 10 mm]}\n"
      "contact: {use: hooke_slider, v_max: 1 m/s, overlap_max: 10 um, restitution: 0.7, friction: 0}\n"
      "particles: {file: p.csv, density: 2500 kg/m^3}\n"
      "walls:\n"
      "  - {type: block, name: floor, lo: [-15 mm, -5 mm, -2 mm], hi: [0 mm, 5 mm, 0 mm]}\n"
      "  - {type: block, name: step, lo: [-5 mm, -5 mm, 0 mm], hi: [0 mm, 5 mm, 3 mm]}\n"
      "  - {type: block, name: piston, lo: [5 mm, -5 mm, -2 mm], hi: [15 mm, 5 mm, 0 mm],\n"
      "     velocity: [0, 0, 10 mm/s], start: 10 ms, stop: 20 ms}\n"
      "run: {duration: 40 ms, dt: 0.1 us, output_every: 10 ms}\n",
      "x,y,z,vx,radius,id\n-10e-3,0,1e-3,0.2,1e-3,0\n10e-3,0,1e-3,0,1e-3,1\n");
  ASSERT_EQ(n, 5u);
  const auto last = particles(n - 1);
  for (const auto &row : last) {
    if (row.at("id") == 0) {
      std::printf("step rebound %.9g m/s, closed form %.9g m/s; height %.6g mm\n", row.at("vx"), -e * 0.2,
                  row.at("z") * 1e3);
      EXPECT_NEAR(row.at("vx"), -e * 0.2, 1e-3 * e * 0.2);
      EXPECT_NEAR(row.at("z"), 1e-3, 1e-6) << "it left the floor";
    } else {
      std::printf("lifted by the piston: %.6g um (its travel 100 um)\n", (row.at("z") - 1e-3) * 1e6);
      EXPECT_NEAR(row.at("z") - 1e-3, 100e-6, 1e-6);
    }
  }
}

TEST_F(WrittenScenes, APlaneThatStopsHasCarriedItsSphereByItsTravel) {
  // A floor plane rising at 10 mm/s from 0 to 10 ms (started at once, stopped on the way) lifts the
  // sphere resting on it by 100 um, and then rests.
  const std::size_t n = simulate_written(
      "name: lift\ndomain: {lo: [-5 mm, -5 mm, -1 mm], hi: [5 mm, 5 mm, 5 mm]}\n"
      "contact: {use: hooke_slider, v_max: 1 m/s, overlap_max: 10 um, restitution: 0.7}\n"
      "particles: {file: p.csv, density: 2500 kg/m^3}\n"
      "walls:\n  - {type: plane, point: [0, 0, 0], normal: [0, 0, 1], velocity: [0, 0, 10 mm/s], stop: 10 ms}\n"
      "run: {duration: 30 ms, dt: 0.1 us, output_every: 10 ms}\n",
      "x,y,z,radius,id\n0,0,1e-3,1e-3,0\n");
  ASSERT_EQ(n, 4u);
  const double rise = particles(n - 1).front().at("z") - 1e-3;
  std::printf("lifted by the plane: %.6g um (its travel 100 um)\n", rise * 1e6);
  EXPECT_NEAR(rise, 100e-6, 1e-6);
}

// A spreader short of open sides is a warning, not a refusal; a process says it once per file however
// often the scene is resolved (once per stage of a run; here the same file validated twice).
TEST_F(Scenes, ASpreaderShortOfOpenSidesIsWarnedOnceAndAccepted) {
  const fs::path file = dir_ / "open.yaml";
  std::ofstream(file) << "version: 1\nname: open\nscene:\n  preset: quick\n"
                         "  domain: {width: 40 mm, periodic_y: false}\n"
                         "  spreader: {length: 20 mm, y_centre: 20 mm}\n"
                         "stages:\n  - simulate: {}\n";
  const auto r = t::run({{"validate", file.string(), file.string()}, {}, {}, {}});
  EXPECT_EQ(r.exit_code, 0) << r.describe();
  const std::string warning = "the spreader spans y = 10..30 mm, the domain 0..40 mm: the powder beyond its ends";
  const std::size_t first = r.err.find(warning);
  ASSERT_NE(first, std::string::npos) << r.err;
  EXPECT_EQ(r.err.find(warning, first + 1), std::string::npos) << "said more than once:\n" << r.err;
  EXPECT_NE(r.err.find("make spreader.length at least 40 mm and set spreader.y_centre: 20 mm"), std::string::npos);
}
