// Closed-form physics of the engine with the test spring-dashpot law: static overlap under
// gravity, momentum conservation, energy conservation without dissipation, and the sharpness of
// the critical time step.
#include "unit/engine_test_law.hpp"

#include <engine/errors.hpp>
#include <engine/stability.hpp>

#include <gtest/gtest.h>
#include <limits>
#include <random>

namespace sm = spreadmap;
using namespace sm::engine;
using namespace sm::engine::testing;

namespace {

Settings quiet() {
  Settings s;
  s.log = [](const std::string &) {};
  return s;
}

constexpr double density = 2500, radius = 0.001, stiffness = 100;  // m = 1.05e-5 kg, omega = 3.1e3 rad/s
const Domain open_box{{0, 0, 0}, {0.01, 0.01, 0.01}, {false, false, false}};

template <class Real> double resting_overlap() {
  TestSpringDashpot law = TestSpringDashpot::with_restitution(stiffness, 0.5);
  Simulation<Real> sim(open_box, bind(law), quiet());
  sim.add_plane_wall({{0, 0, 0}, {0, 0, 1}, {0, 0, 0}, bind(law), true, "floor"});
  ParticleSet p;
  push_particle(p, 0.005, 0.005, radius, radius);
  sim.add_particles(p, density);
  // Damping time 1 / (zeta omega) = 1.5 ms: 40 ms leaves exp(-27) of the initial transient.
  sim.run_until(0.04);
  return radius - double(sim.arrays().z[0]);
}

}  // namespace

TEST(EngineStatics, SphereOnPlaneSettlesAtMgOverK) {
  // Equilibrium K delta = m g. Tolerance 0.5 % (brief); double resolves delta = 1e-6 m to ~1e-13.
  const double expected = sphere_mass(radius, density) * 9.81 / stiffness;
  EXPECT_NEAR(resting_overlap<double>(), expected, 0.005 * expected);
}

TEST(EngineStatics, FloatSettlesToo) {
  // Float positions near 1e-3 m carry ~6e-11 m of rounding against delta = 1e-6 m: 0.5 % holds.
  const double expected = sphere_mass(radius, density) * 9.81 / stiffness;
  EXPECT_NEAR(resting_overlap<float>(), expected, 0.005 * expected);
}

TEST(EngineDynamics, HeadOnImpactConservesMomentum) {
  // Unequal spheres, damped contact, no gravity. The full list computes F_ij and F_ji from exactly
  // negated geometry, so the forces cancel to the bit; what remains is the rounding of m v sums.
  TestSpringDashpot law = TestSpringDashpot::with_restitution(stiffness, 0.7);
  Settings s = quiet();
  s.gravity = {0, 0, 0};
  Simulation<double> sim({{0, 0, 0}, {0.1, 0.01, 0.01}, {false, false, false}}, bind(law), s);
  ParticleSet p;
  push_particle(p, 0.044, 0.005, 0.005, 0.001, 0.5, 0, 0);
  push_particle(p, 0.0468, 0.005, 0.005, 0.0015, -0.3, 0, 0);
  sim.add_particles(p, density);
  auto momentum = [&] {
    const auto st = sim.state();
    double px = 0, scale = 0;
    for (std::size_t i = 0; i < st.size(); ++i) {
      px += st.mass[i] * st.vx[i];
      scale += st.mass[i] * std::abs(st.vx[i]);
    }
    return std::pair{px, scale};
  };
  const auto [p0, scale] = momentum();
  for (int k = 0; k < 400; ++k) {
    sim.step();
    EXPECT_NEAR(momentum().first, p0, 1e-12 * scale) << "step " << k;
  }
  EXPECT_EQ(sim.size(), 2u);
  const auto st = sim.state();
  const std::size_t a = st.id[0] == 0 ? 0 : 1, b = 1 - a;
  EXPECT_LT(st.vx[a], st.vx[b]) << "the spheres should have bounced apart";
  EXPECT_LT(st.vx[a], 0.0);
}

TEST(EngineDynamics, ElasticFrictionlessBoxConservesEnergy) {
  // 30 spheres bouncing in a closed box under gravity with e = 1, mu = 0: total energy (kinetic +
  // gravitational + spring) drifts by less than 0.1 % over 1e5 steps (brief). Velocity-Verlet is
  // symplectic; the only error source is the kink of the force at contact onset.
  TestSpringDashpot law = TestSpringDashpot::with_restitution(stiffness, 1.0);
  Settings s = quiet();
  // The drift comes from the force kink at contact onset and falls steeply with dt (measured with
  // this scene: 8 % at 0.2 dt_crit, 0.6 % at 0.1, 0.07 % at 0.05, 0.015 % at 0.025), so this test
  // runs at 0.05 dt_crit (about 60 steps per contact).
  s.dt_safety = 0.05;
  const double L = 0.012, r = 0.001;
  Simulation<double> sim({{-0.001, -0.001, -0.001}, {L + 0.001, L + 0.001, L + 0.001}, {false, false, false}},
                         bind(law), s);
  const std::array<std::array<double, 3>, 6> normals = {
      {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}}};
  for (const auto &n : normals) {
    std::array<double, 3> point{0, 0, 0};
    for (int a = 0; a < 3; ++a) point[a] = n[a] < 0 ? L : 0;
    sim.add_plane_wall({point, n, {0, 0, 0}, bind(law), true, "box"});
  }
  ParticleSet p;
  for (int k = 0; k < 30; ++k) {
    const int ix = k % 4, iy = (k / 4) % 4, iz = k / 16;
    push_particle(p, 0.0015 + 0.003 * ix, 0.0015 + 0.003 * iy, 0.0015 + 0.003 * iz, r, 0.2 * std::sin(k * 1.3),
                  0.2 * std::cos(k * 2.1), 0.15 * std::sin(k * 0.7 + 1));
  }
  p.radius.assign(30, r);
  sim.add_particles(p, density);
  const double g = 9.81;
  auto energy = [&] {
    const auto &q = sim.arrays();
    double e = 0;
    for (std::size_t i = 0; i < q.size(); ++i) {
      e += 0.5 * q.m[i] * (q.vx[i] * q.vx[i] + q.vy[i] * q.vy[i] + q.vz[i] * q.vz[i]) + q.m[i] * g * q.z[i];
      for (std::size_t j = i + 1; j < q.size(); ++j) {
        const double d =
            std::sqrt(std::pow(q.x[i] - q.x[j], 2) + std::pow(q.y[i] - q.y[j], 2) + std::pow(q.z[i] - q.z[j], 2));
        const double overlap = q.r[i] + q.r[j] - d;
        if (overlap > 0) e += 0.5 * stiffness * overlap * overlap;
      }
      const double pos[3] = {q.x[i], q.y[i], q.z[i]};
      for (int a = 0; a < 3; ++a) {
        const double lo = q.r[i] - pos[a], hi = pos[a] + q.r[i] - L;
        if (lo > 0) e += 0.5 * stiffness * lo * lo;
        if (hi > 0) e += 0.5 * stiffness * hi * hi;
      }
    }
    return e;
  };
  const double e0 = energy();
  double worst = 0;
  for (int block = 0; block < 100; ++block) {
    sim.run_steps(1000);
    worst = std::max(worst, std::abs(energy() - e0) / e0);
  }
  EXPECT_EQ(sim.step_count(), 100000u);
  EXPECT_EQ(sim.removed_count(), 0u);
  EXPECT_LT(worst, 1e-3);
  RecordProperty("max_relative_energy_drift", std::to_string(worst));
  std::printf("max relative energy drift over 1e5 steps: %.3g\n", worst);
}

namespace {

// A sphere resting on a plane under gravity, nudged by `nudge` x its static overlap, integrated at
// `factor` x dt_crit. Returns the largest and the final perturbation energy relative to the start
// (kinetic + spring about the equilibrium), or stops early at the engine's RunError.
struct Growth {
  double largest = 0, last = 0;
  bool run_error = false;
};
Growth perturbation_growth(double restitution, double factor, int steps) {
  TestSpringDashpot law = TestSpringDashpot::with_restitution(stiffness, restitution);
  const double m = sphere_mass(radius, density), g = 9.81, eq = m * g / stiffness, nudge = 1e-3 * eq;
  Settings probe_settings = quiet();
  Simulation<double> probe(open_box, bind(law), probe_settings);
  probe.add_plane_wall({{0, 0, 0}, {0, 0, 1}, {0, 0, 0}, bind(law)});
  ParticleSet p;
  push_particle(p, 0.005, 0.005, radius - eq - nudge, radius);
  probe.add_particles(p, density);
  Settings s = quiet();
  s.dt = factor * contact_critical_dt(bind(law), m, radius);  // one contact: wall, m_eq = m
  s.allow_unstable_dt = true;
  Simulation<double> sim(open_box, bind(law), s);
  sim.add_plane_wall({{0, 0, 0}, {0, 0, 1}, {0, 0, 0}, bind(law)});
  sim.add_particles(p, density);
  auto energy = [&] {
    const double v = sim.arrays().vz[0], dz = (radius - eq) - sim.arrays().z[0];
    return 0.5 * m * v * v + 0.5 * stiffness * dz * dz;
  };
  const double e0 = energy();
  Growth out;
  try {
    for (int k = 0; k < steps; ++k) {
      sim.step();
      out.last = energy() / e0;
      out.largest = std::max(out.largest, out.last);
    }
  } catch (const RunError &) {
    out.run_error = true;
  }
  return out;
}

}  // namespace

TEST(EngineTimeStep, SingleContactLimitIsSharp) {
  // One contact's limit (contact_critical_dt, 2 to 3.5 x the scene's dt_crit, stability.hpp).
  // At 0.9 x the limit the perturbation decays (damped) or stays bounded (e = 1); at 1.1 x it
  // grows by orders of magnitude within a few dozen steps. The nudge (1e-3 of the static overlap)
  // keeps the sphere in contact, where the linear analysis holds, up to a growth of 1e6.
  for (double e : {0.1, 0.5, 0.9}) {
    const Growth stable = perturbation_growth(e, 0.9, 2000);
    EXPECT_FALSE(stable.run_error) << "e = " << e;
    EXPECT_LT(stable.last, 1e-6) << "e = " << e;
    const Growth unstable = perturbation_growth(e, 1.1, 2000);
    EXPECT_GT(unstable.largest, 1e5) << "e = " << e;
  }
  const Growth elastic = perturbation_growth(1.0, 0.9, 2000);
  EXPECT_FALSE(elastic.run_error);
  EXPECT_LT(elastic.largest, 100.0);  // bounded: at omega dt = 1.8 the discrete energy is distorted, not growing
  EXPECT_GT(perturbation_growth(1.0, 1.1, 2000).largest, 1e5);
}

namespace {

// A face-centred cubic crystal of 4 x 3^3 spheres filling a periodic box, every contact compressed
// by 1 % of the diameter (the forces balance by symmetry), each sphere displaced at random by 1e-4
// of that overlap. Integrated at `factor` x dt_crit for `steps` steps; returns the largest
// displacement from the lattice relative to the initial one, or stops early at the engine's RunError.
Growth fcc_growth(double restitution, double factor, int steps) {
  TestSpringDashpot law = TestSpringDashpot::with_restitution(stiffness, restitution);
  const int cells = 3;
  const double r = radius, gap = 2 * r * 0.99, a = gap * std::sqrt(2.0), side = cells * a;
  const Domain box{{0, 0, 0}, {side, side, side}, {true, true, true}};
  ParticleSet p;
  std::vector<std::array<double, 3>> lattice;
  const double basis[4][3] = {{0, 0, 0}, {0.5, 0.5, 0}, {0.5, 0, 0.5}, {0, 0.5, 0.5}};
  for (int i = 0; i < cells; ++i)
    for (int j = 0; j < cells; ++j)
      for (int k = 0; k < cells; ++k)
        for (const auto &b : basis)
          lattice.push_back({(i + b[0] + 0.25) * a, (j + b[1] + 0.25) * a, (k + b[2] + 0.25) * a});
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  const double kick = 1e-4 * (2 * r - gap);
  for (const auto &q : lattice) push_particle(p, q[0] + kick * u(rng), q[1] + kick * u(rng), q[2] + kick * u(rng), r);
  Settings s = quiet();
  s.gravity = {0, 0, 0};
  Simulation<double> probe(box, bind(law), s);
  probe.add_particles(p, density);
  s.dt = factor * probe.critical_dt();
  s.allow_unstable_dt = true;
  Simulation<double> sim(box, bind(law), s);
  sim.add_particles(p, density);
  auto largest_offset = [&] {
    const ParticleSet now = sim.state();
    double worst = 0;
    for (std::size_t i = 0; i < now.x.size(); ++i) {
      const auto &q = lattice[now.id[i]];
      double d2 = 0;
      for (int c = 0; c < 3; ++c) {
        double d = (c == 0 ? now.x[i] : c == 1 ? now.y[i] : now.z[i]) - q[c];
        d -= side * std::round(d / side);
        d2 += d * d;
      }
      worst = std::max(worst, std::sqrt(d2));
    }
    return worst;
  };
  const double start = largest_offset();
  Growth out;
  try {
    for (int k = 0; k < steps; ++k) {
      sim.step();
      if (k % 10 == 9) {
        out.last = largest_offset() / start;
        out.largest = std::max(out.largest, out.last);
      }
    }
  } catch (const RunError &) {
    out.run_error = true;
    out.largest = std::numeric_limits<double>::infinity();
  }
  return out;
}

}  // namespace

TEST(EngineTimeStep, SceneLimitIsSharpForTheDensestPacking) {
  // dt_crit is the limit of the fastest mode of a face-centred cubic packing, twice a contact's
  // frequency with twice its damping ratio (stability.hpp). A perturbed crystal stays near its
  // lattice at 0.9 x dt_crit and its fastest mode runs away at 1.1 x.
  for (double e : {1.0, 0.8, 0.3}) {
    const Growth stable = fcc_growth(e, 0.9, 3000);
    EXPECT_FALSE(stable.run_error) << "e = " << e;
    EXPECT_LT(stable.largest, 10.0) << "e = " << e;
    const Growth unstable = fcc_growth(e, 1.1, 3000);
    EXPECT_GT(unstable.largest, 1e4) << "e = " << e;
  }
}

TEST(EngineRunChecks, DeepOverlapStopsWithAClearMessage) {
  // A sphere sunk 20 % of its diameter into the floor (limit 10 %): the first check stops the run
  // and says what to change.
  TestSpringDashpot law = TestSpringDashpot::with_restitution(stiffness, 0.5);
  Settings s = quiet();
  s.check_every = 1;
  Simulation<double> sim(open_box, bind(law), s);
  sim.add_plane_wall({{0, 0, 0}, {0, 0, 1}, {0, 0, 0}, bind(law), true, "floor"});
  ParticleSet p;
  push_particle(p, 0.005, 0.005, radius - 0.4 * radius, radius);
  sim.add_particles(p, density);
  try {
    sim.step();
    FAIL() << "a 20 % overlap was accepted";
  } catch (const RunError &e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("overlap too large"), std::string::npos) << what;
    EXPECT_NE(what.find("plane wall 'floor'"), std::string::npos) << what;
    EXPECT_NE(what.find("smaller dt"), std::string::npos) << what;
  }
}

TEST(EngineRunChecks, NaNStopsWithAClearMessage) {
  // A law that returns NaN (here: a NaN stiffness) must stop the run at the step it happens.
  TestSpringDashpot law{std::numeric_limits<double>::quiet_NaN(), 0, 0};
  Settings s = quiet();
  s.dt = 1e-5;
  Simulation<double> sim(open_box, bind(law), s);
  sim.add_plane_wall({{0, 0, 0}, {0, 0, 1}, {0, 0, 0}, bind(law), true, "floor"});
  ParticleSet p;
  push_particle(p, 0.005, 0.005, 0.99 * radius, radius);
  sim.add_particles(p, density);
  try {
    sim.run_steps(10);
    FAIL() << "NaN forces were accepted";
  } catch (const RunError &e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("NaN"), std::string::npos) << what;
    EXPECT_NE(what.find("step 1)"), std::string::npos) << what;
  }
}
