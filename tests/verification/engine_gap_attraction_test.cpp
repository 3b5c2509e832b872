// The engine hands a law that attracts across a gap (the van der Waals part of contact_parts.hpp) the
// pairs and plane records it reaches: its neighbour list reaches the law's range beyond the skin, both
// plane paths (records in place and the gathered subset) keep gaps down to -range, and nothing acts
// beyond the cut-off. Checked against the force's closed form over one step: a sphere at rest at gap g
// gains v = F dt / m, F = A r_eff / (6 g^2). Suite named in lower case for `ctest -R cohesion`.
#include "plugins/contact/hooke_slider/hooke_slider.hpp"
#include "verification/contact_support.hpp"

#include <engine/errors.hpp>
#include <engine/simulation.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace sm = spreadmap;
using namespace sm::engine;

namespace {

constexpr double hamaker = 1e-17, min_gap = 1e-7, cutoff = 5e-5;  // [J], [m], [m]
constexpr double radius = 125e-6, density = 4430;                 // [m], [kg/m^3]
const double mass = density * 4.0 / 3.0 * sm::pi * radius * radius * radius;

sm::HookeSlider vdw_law() {
  return sm::test::bind_law<sm::HookeSlider>(
      {{"hamaker_constant", hamaker}, {"vdw_min_gap", min_gap}, {"vdw_cutoff", cutoff}});
}

Settings quiet(bool planes_in_place = true) {
  Settings s;
  s.log = [](const std::string &) {};
  s.gravity = {0, 0, 0};
  s.skin = 5e-6;  // a tenth of the cut-off: pairs at a gap beyond it are listed only through the law's range
  s.planes_in_place = planes_in_place;
  return s;
}

void add_sphere(Simulation<double> &sim, double x, double y, double z) {
  ParticleSet p;
  p.x = {x};
  p.y = {y};
  p.z = {z};
  p.radius = {radius};
  p.vx = p.vy = p.vz = p.wx = p.wy = p.wz = {0.0};
  sim.add_particles(p, density);
}

double force_at(double gap, double r_eff) { return gap < cutoff ? hamaker * r_eff / (6 * gap * gap) : 0.0; }

}  // namespace

TEST(cohesion_engine, ContactOpsDeclareTheLawsRange) {
  const sm::HookeSlider law = vdw_law(), plain = sm::test::bind_law<sm::HookeSlider>();
  EXPECT_EQ(sm::detail::ContactOps<sm::HookeSlider>::table.range(&law), cutoff);
  EXPECT_EQ(sm::detail::ContactOps<sm::HookeSlider>::table.range(&plain), 0.0);
}

// Two spheres 30 um apart, 6 skins: listed only because the list reaches the law's range.
TEST(cohesion_engine, SpheresFartherApartThanTheSkinAttractAcrossTheGap) {
  const sm::HookeSlider law = vdw_law();
  const ContactLaw bound{&sm::detail::ContactOps<sm::HookeSlider>::table, &law};
  for (const double gap : {30e-6, 1.2 * cutoff}) {
    Simulation<double> sim({{0, 0, 0}, {0.004, 0.004, 0.004}, {false, false, false}}, bound, quiet());
    add_sphere(sim, 0.002 - radius - gap / 2, 0.002, 0.002);
    add_sphere(sim, 0.002 + radius + gap / 2, 0.002, 0.002);
    sim.step();
    const auto &p = sim.arrays();
    const double expected = force_at(gap, radius / 2) * sim.dt() / mass;
    const std::size_t left = p.x[0] < p.x[1] ? 0 : 1, right = 1 - left;
    EXPECT_NEAR(p.vx[left], expected, 1e-6 * expected + 1e-300) << "gap " << gap;
    EXPECT_NEAR(p.vx[right], -expected, 1e-6 * expected + 1e-300) << "gap " << gap;
    EXPECT_EQ(p.vy[left], 0.0);
    EXPECT_EQ(p.vz[left], 0.0);
  }
}

// A sphere 30 um above the floor (r_eff = r), through both of the engine's plane paths.
TEST(cohesion_engine, APlateAttractsAcrossTheGapThroughBothPlanePaths) {
  const sm::HookeSlider law = vdw_law();
  const ContactLaw bound{&sm::detail::ContactOps<sm::HookeSlider>::table, &law};
  for (const bool in_place : {true, false}) {
    for (const double gap : {30e-6, 1.2 * cutoff}) {
      Simulation<double> sim({{0, 0, 0}, {0.004, 0.004, 0.004}, {false, false, false}}, bound, quiet(in_place));
      sim.add_plane_wall({{0, 0, 0}, {0, 0, 1}, {0, 0, 0}, bound, true, "floor"});
      add_sphere(sim, 0.002, 0.002, radius + gap);
      sim.step();
      const double expected = force_at(gap, radius) * sim.dt() / mass;
      EXPECT_NEAR(sim.arrays().vz[0], -expected, 1e-6 * expected + 1e-300)
          << (in_place ? "records in place" : "gathered subset") << ", gap " << gap;
    }
  }
}

// Sleeping stops integrating particles at rest and wakes them on touch: a sphere pulled across a gap
// would not move. The engine refuses the pair, naming the key that makes the law reach.
TEST(cohesion_engine, SleepWithAttractionAcrossAGapIsRefused) {
  const sm::HookeSlider law = vdw_law();
  const ContactLaw bound{&sm::detail::ContactOps<sm::HookeSlider>::table, &law};
  Settings s = quiet();
  s.sleep = true;
  try {
    Simulation<double> sim({{0, 0, 0}, {0.004, 0.004, 0.004}, {false, false, false}}, bound, s);
    FAIL() << "accepted";
  } catch (const SetupError &e) {
    EXPECT_NE(std::string(e.what()).find("hamaker_constant"), std::string::npos) << e.what();
  }
}
