// Engine mechanics: stability formula, time-step refusal, removal, periodic wrapping, determinism
// across threads and runs, checkpoint/resume, history carried over list rebuilds.
#include "engine_test_law.hpp"
#include "plugins/contact/hooke_slider/hooke_slider.hpp"
#include "temporaries.hpp"

#include <engine/binary_io.hpp>
#include <engine/errors.hpp>
#include <engine/stability.hpp>

#include <complex>
#include <fmt/format.h>
#include <unistd.h>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <gtest/gtest.h>
#include <omp.h>

namespace sm = spreadmap;
using namespace sm::engine;
using namespace sm::engine::testing;

namespace {

// Spectral radius of the one-step map of the contact oscillator (see stability.hpp).
double spectral_radius(double a, double zeta) {
  const double t = 2 - 2 * zeta * a - a * a, d = 1 - 2 * zeta * a;
  const std::complex<double> disc = std::sqrt(std::complex<double>(t * t - 4 * d));
  return std::max(std::abs((t + disc) / 2.0), std::abs((t - disc) / 2.0));
}

template <class Real> bool same_bits(const std::vector<Real> &a, const std::vector<Real> &b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(Real)) == 0;
}

// The states in id order (the engine's storage order is its own business).
template <class Real> ParticleArrays<Real> by_id(const ParticleArrays<Real> &p) {
  std::vector<std::uint32_t> order(p.size());
  for (std::uint32_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](auto a, auto b) { return p.id[a] < p.id[b]; });
  ParticleArrays<Real> out = p;
  std::vector<Real> scratch;
  std::vector<std::uint32_t> scratch_index;
  out.for_each_real([&](std::vector<Real> &c) { gather(c, order, scratch); });
  out.for_each_index([&](std::vector<std::uint32_t> &c) { gather(c, order, scratch_index); });
  return out;
}

template <class Real> bool same_state(const Simulation<Real> &a, const Simulation<Real> &b) {
  const auto p = by_id(a.arrays()), q = by_id(b.arrays());
  return same_bits(p.x, q.x) && same_bits(p.y, q.y) && same_bits(p.z, q.z) && same_bits(p.vx, q.vx) &&
         same_bits(p.vy, q.vy) && same_bits(p.vz, q.vz) && same_bits(p.wx, q.wx) && same_bits(p.wy, q.wy) &&
         same_bits(p.wz, q.wz) && p.id == q.id && a.time() == b.time();
}

Settings quiet() {
  Settings s;
  s.log = [](const std::string &) {};
  s.parallel_min_particles = 0;  // small test scenes still run with every thread
  return s;
}

// A small granular scene that exercises everything: periodic x and y, open z, a floor, friction
// (tangential history), polydisperse spheres falling and colliding, several list rebuilds.
template <class Real> struct Scene {
  TestSpringDashpot pair = TestSpringDashpot::with_restitution(50, 0.6, 0.4);
  TestSpringDashpot wall = TestSpringDashpot::with_restitution(100, 0.6, 0.3);
  Domain domain{{0, 0, 0}, {0.012, 0.012, 0.05}, {true, true, false}};
  Simulation<Real> make(std::size_t n = 300) {
    Simulation<Real> sim(domain, bind(pair), quiet());
    sim.add_plane_wall({{0, 0, 0}, {0, 0, 1}, {0, 0, 0}, bind(wall), true, "floor"});
    sim.add_particles(random_lattice(n, 0.0005, {0, 0, 0.0006}, {0.012, 0.012, 0.04}, 0.2), 2500);
    return sim;
  }
};

}  // namespace

TEST(EngineStability, FormulaIsTheJuryLimit) {
  // Just below the limit every eigenvalue is inside the unit circle, just above one is outside.
  for (double zeta : {0.0, 0.05, 0.2155, 0.5, 0.59, 1.0, 3.0}) {
    const double a = stable_omega_dt(zeta);
    // zeta = 0: undamped, eigenvalues on the unit circle (neutral) below the limit
    EXPECT_LT(spectral_radius(0.999 * a, zeta), zeta > 0 ? 1.0 : 1.0 + 1e-12) << "zeta " << zeta;
    EXPECT_GT(spectral_radius(1.001 * a, zeta), 1.0) << "zeta " << zeta;
  }
  EXPECT_DOUBLE_EQ(stable_omega_dt(0), 2.0);
}

TEST(EngineTimeStep, RefusesAStepAboveCritical) {
  TestSpringDashpot law = TestSpringDashpot::with_restitution(100, 0.5);
  Settings s = quiet();
  Domain d{{0, 0, 0}, {0.01, 0.01, 0.01}, {false, false, false}};
  ParticleSet p;
  push_particle(p, 0.005, 0.005, 0.001, 0.001);
  {
    Simulation<double> probe(d, bind(law), s);
    probe.add_plane_wall({{0, 0, 0}, {0, 0, 1}, {0, 0, 0}, bind(law)});
    probe.add_particles(p, 2500);
    s.dt = 1.5 * probe.critical_dt();
    // wall contact: m_eq = m, omega = sqrt(K/m); the densest packing's mode is 2 omega with damping
    // ratio 2 zeta, so dt_crit = 2 (sqrt(1 + 4 z^2) - 2 z) / (2 omega)
    const double m = sphere_mass(0.001, 2500);
    EXPECT_NEAR(probe.critical_dt(), stable_omega_dt(2 * law.zeta) / (2 * std::sqrt(100 / m)), 1e-15);
    EXPECT_NEAR(probe.dt(), 0.4 * probe.critical_dt(), 1e-18);
  }
  Simulation<double> sim(d, bind(law), s);
  sim.add_plane_wall({{0, 0, 0}, {0, 0, 1}, {0, 0, 0}, bind(law)});
  sim.add_particles(p, 2500);
  try {
    sim.step();
    FAIL() << "a step 1.5 x dt_crit was accepted";
  } catch (const SetupError &e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(fmt::format("{:.6g}", s.dt)), std::string::npos) << what;
    EXPECT_NE(what.find(fmt::format("{:.6g}", sim.critical_dt())), std::string::npos) << what;
  }
}

// SJKR cohesion that cancels a Hooke law's spring (k_c >= K_n / (2 pi r_eff): 2.66e4 J/m^3 for 30 um
// Ti-6Al-4V spheres with the default V_max / Delta_max) collapses contacts at any step: the law says so
// with an infinite frequency, and the engine refuses the scene before the first step, naming the fix.
TEST(EngineTimeStep, RefusesACohesionThatCollapsesContacts) {
  nlohmann::json params = nlohmann::json::object();
  for (const sm_param_v1 &q : sm::HookeSlider::params)
    if (q.type == SM_NUMBER) params[q.name] = q.def;
    else if (q.type == SM_BOOLEAN) params[q.name] = q.def != 0;
    else params[q.name] = q.def_text;
  params["cohesion_energy_density"] = 4e4;
  const sm::HookeSlider law = sm::HookeSlider::bind(sm::Values(params));
  const ContactLaw bound{&sm::detail::ContactOps<sm::HookeSlider>::table, &law};
  ParticleSet p;
  push_particle(p, 0.005, 0.005, 0.001, 15e-6);
  Simulation<double> sim({{0, 0, 0}, {0.01, 0.01, 0.01}, {false, false, false}}, bound, quiet());
  sim.add_plane_wall({{0, 0, 0}, {0, 0, 1}, {0, 0, 0}, bound});
  sim.add_particles(p, 4430);
  EXPECT_EQ(sim.critical_dt(), 0.0);
  try {
    sim.step();
    FAIL() << "a collapsing cohesion was accepted";
  } catch (const SetupError &e) {
    EXPECT_NE(std::string(e.what()).find("no time step is stable"), std::string::npos) << e.what();
  }
}

TEST(EngineRotation, SkippedAndLoggedWithoutTorque) {
  TestSpringDashpot law = TestSpringDashpot::with_restitution(100, 0.5, 0.0);
  std::string logged;
  Settings s;
  s.log = [&](const std::string &m) { logged += m + "\n"; };
  Simulation<double> sim({{0, 0, 0}, {0.01, 0.01, 0.01}, {false, false, false}}, bind(law), s);
  sim.add_plane_wall({{0, 0, 0}, {0, 0, 1}, {0, 0, 0}, bind(law)});
  ParticleSet p;
  push_particle(p, 0.005, 0.005, 0.005, 0.001);
  p.wz = {3.0};
  sim.add_particles(p, 2500);
  sim.step();
  EXPECT_FALSE(sim.rotation_integrated());
  EXPECT_NE(logged.find("rotation is not integrated"), std::string::npos) << logged;
  EXPECT_EQ(sim.arrays().wz[0], 3.0);
}

TEST(EngineRemoval, CountsParticlesLeavingOpenFacesAndWrapsPeriodicOnes) {
  TestSpringDashpot law = TestSpringDashpot::with_restitution(100, 0.5);
  Settings s = quiet();
  s.gravity = {0, 0, 0};
  s.speed_limit = 100;
  Simulation<double> sim({{0, 0, 0}, {0.02, 0.02, 0.02}, {true, false, false}}, bind(law), s);
  ParticleSet p;
  // ids 0-4 leave through z = hi, 5 through y = lo, 6-8 cross the periodic x faces, 9 stays.
  for (int k = 0; k < 5; ++k) push_particle(p, 0.002 + 0.003 * k, 0.01, 0.018, 0.0005, 0, 0, 1.0);
  push_particle(p, 0.01, 0.001, 0.01, 0.0005, 0, -1.0, 0);
  push_particle(p, 0.019, 0.005, 0.005, 0.0005, 1.0, 0, 0);
  push_particle(p, 0.001, 0.007, 0.005, 0.0005, -1.0, 0, 0);
  push_particle(p, 0.019, 0.013, 0.005, 0.0005, 2.0, 0, 0);
  push_particle(p, 0.01, 0.01, 0.01, 0.0005);
  sim.add_particles(p, 2500);
  while (sim.time() < 0.01) sim.step();  // 1 m/s over 10 ms: 10 mm, more than any distance to a face
  EXPECT_EQ(sim.removed_count(), 6u);
  EXPECT_EQ(sim.size(), 4u);
  auto ids = sim.state().id;
  std::sort(ids.begin(), ids.end());
  EXPECT_EQ(ids, (std::vector<std::uint32_t>{6, 7, 8, 9}));
  for (double x : sim.state().x) {
    EXPECT_GE(x, 0.0);
    EXPECT_LT(x, 0.02);
  }
}

// A particle that leaves is removed at the next list build, not at once (an open-sided plate loses
// some almost every step): until then state(), size() and removed_count() already count it out,
// while the arrays still hold it; the build that the other particle's motion schedules removes it.
TEST(EngineRemoval, ALeavingParticleIsRemovedAtTheNextListBuild) {
  TestSpringDashpot law = TestSpringDashpot::with_restitution(100, 0.5);
  Settings s = quiet();
  s.gravity = {0, 0, 0};
  s.speed_limit = 100;
  s.skin = 2e-4;  // a rebuild once something moved 0.1 mm
  Simulation<double> sim({{0, 0, 0}, {0.02, 0.02, 0.02}, {false, false, false}}, bind(law), s);
  ParticleSet p;
  push_particle(p, 0.019999, 0.01, 0.01, 0.0005, 0.01, 0, 0);  // id 0: crosses x = hi within 0.1 ms, slowly
  push_particle(p, 0.005, 0.01, 0.01, 0.0005, 0.5, 0, 0);      // id 1: half a skin in 0.2 ms
  sim.add_particles(p, 2500);
  sim.step();
  const std::uint64_t builds = sim.counters().list_builds;
  while (sim.arrays().x[0] < 0.02 && sim.arrays().x[1] < 0.02) sim.step();
  ASSERT_EQ(sim.counters().list_builds, builds) << "no build yet: the leaving one is still held";
  EXPECT_EQ(sim.arrays().size(), 2u);
  EXPECT_EQ(sim.size(), 1u);
  EXPECT_EQ(sim.removed_count(), 1u);
  EXPECT_EQ(sim.state().id, (std::vector<std::uint32_t>{1}));
  while (sim.counters().list_builds == builds) sim.step();  // particle 1 has moved half a skin
  EXPECT_EQ(sim.arrays().size(), 1u);
  EXPECT_EQ(sim.size(), 1u);
  EXPECT_EQ(sim.removed_count(), 1u);
  EXPECT_EQ(sim.state().id, (std::vector<std::uint32_t>{1}));
}

TEST(EnginePeriodic, CollisionAcrossTheBoundaryEqualsOneInside) {
  // The same oblique frictional collision, once straddling the periodic x faces and once in the
  // middle. Positions differ by a domain length, so they round differently: with |x| ~ 1e-2 m and
  // overlaps ~ 1e-5 m, position rounding (~1e-18 m) perturbs velocities at ~1e-13 relative; the
  // tolerance 1e-9 is far above that and far below any physical difference.
  TestSpringDashpot law = TestSpringDashpot::with_restitution(200, 0.7, 0.3);
  Settings s = quiet();
  s.gravity = {0, 0, 0};
  const double L = 0.01, r = 0.0005;
  auto run = [&](double centre) {
    Simulation<double> sim({{0, 0, 0}, {L, L, L}, {true, false, false}}, bind(law), s);
    ParticleSet p;
    push_particle(p, centre - 1.5 * r, 0.005, 0.005, r, 0.3, 0.05, 0);
    push_particle(p, centre + 1.5 * r, 0.005 + 0.6 * r, 0.005, r, -0.2, 0, 0.01);
    sim.add_particles(p, 2500);
    while (sim.time() < 0.01) sim.step();
    auto st = sim.state();
    if (st.id[0] != 0) {  // report in id order
      for (auto *c : {&st.x, &st.y, &st.z, &st.vx, &st.vy, &st.vz, &st.wx, &st.wy, &st.wz}) std::swap((*c)[0], (*c)[1]);
    }
    return st;
  };
  const auto inside = run(0.5 * L), across = run(0.0);
  for (int i = 0; i < 2; ++i) {
    EXPECT_NEAR(across.vx[i], inside.vx[i], 1e-9 * 0.3);
    EXPECT_NEAR(across.vy[i], inside.vy[i], 1e-9 * 0.3);
    EXPECT_NEAR(across.vz[i], inside.vz[i], 1e-9 * 0.3);
    EXPECT_NEAR(across.wx[i], inside.wx[i], 1e-9 * 0.3 / r);
    EXPECT_NEAR(across.wy[i], inside.wy[i], 1e-9 * 0.3 / r);
    EXPECT_NEAR(across.wz[i], inside.wz[i], 1e-9 * 0.3 / r);
    EXPECT_NEAR(across.y[i], inside.y[i], 1e-12);
  }
  EXPECT_NE(inside.wz[0], 0.0);  // the collision really was frictional
  // Relative x positions agree (minimum image).
  const double rel_inside = inside.x[1] - inside.x[0];
  double rel_across = across.x[1] - across.x[0];
  rel_across -= L * std::round(rel_across / L);
  EXPECT_NEAR(rel_across, rel_inside, 1e-12);
}

TEST(EngineDeterminism, BitwiseIdenticalForOneAndTwoThreadsAndRunToRun) {
  Scene<double> scene;
  auto run = [&](int threads) {
    omp_set_num_threads(threads);
    auto sim = scene.make();
    sim.run_steps(600);
    omp_set_num_threads(2);
    return sim;
  };
  const auto one = run(1), two = run(2), again = run(2);
  EXPECT_GT(one.counters().list_builds, 2u) << "the scene should rebuild its list several times";
  EXPECT_TRUE(same_state(one, two)) << "1 vs 2 threads differ";
  EXPECT_TRUE(same_state(two, again)) << "two runs with 2 threads differ";
}

TEST(EngineDeterminism, FloatIsBitwiseIdenticalForOneAndTwoThreads) {
  Scene<float> scene;
  omp_set_num_threads(1);
  auto one = scene.make();
  one.run_steps(400);
  omp_set_num_threads(2);
  auto two = scene.make();
  two.run_steps(400);
  EXPECT_TRUE(same_state(one, two));
}

// A step leaves its second half kick to the next step's pass (Simulation::kick_and_drift), and a
// read of the state runs it first: reading the state after every step (two passes a step) or only
// now and then (one pass) gives the same bits. That what is read is the completed step is checked
// against runs that never defer the kick (sleeping scenes: EngineSleep.WhereNoneMaySleepNoBitChanges)
// and by a resume from a checkpoint (EngineCheckpoint.ResumeIsBitwiseIdentical).
TEST(EngineDeterminism, ReadingTheStateBetweenStepsChangesNoBit) {
  Scene<double> scene;
  auto read_every_step = scene.make(), read_rarely = scene.make();
  for (int s = 0; s < 400; ++s) {
    read_every_step.run_steps(1);
    EXPECT_TRUE(std::isfinite(read_every_step.arrays().vz[0]));  // the read runs the pending kick
    read_rarely.run_steps(1);
    if (s == 199) {
      EXPECT_TRUE(same_state(read_every_step, read_rarely)) << "the states read half way differ";
    }
  }
  EXPECT_GT(read_rarely.counters().list_builds, 2u);
  EXPECT_TRUE(same_state(read_every_step, read_rarely));
}

TEST(EngineCheckpoint, ResumeIsBitwiseIdentical) {
  const auto path = std::filesystem::temp_directory_path() / fmt::format("engine_ckpt_{}.bin", ::getpid());
  Scene<double> scene;
  auto whole = scene.make();
  whole.run_steps(300);
  whole.save_checkpoint(path);
  EXPECT_TRUE(temporaries_beside(path).empty());
  whole.run_steps(300);

  Simulation<double> resumed(scene.domain, bind(scene.pair), quiet());
  resumed.add_plane_wall({{0, 0, 0}, {0, 0, 1}, {0, 0, 0}, bind(scene.wall), true, "floor"});
  resumed.load_checkpoint(path);
  EXPECT_EQ(resumed.step_count(), 300u);
  resumed.run_steps(300);
  EXPECT_TRUE(same_state(whole, resumed));
  EXPECT_EQ(whole.counters().list_builds, resumed.counters().list_builds);

  // Mismatched scene: a clear error naming the counts.
  Simulation<double> wrong(scene.domain, bind(scene.pair), quiet());
  try {
    wrong.load_checkpoint(path);
    FAIL() << "a checkpoint with one plane wall loaded into a scene without walls";
  } catch (const SetupError &e) {
    EXPECT_NE(std::string(e.what()).find("1 plane walls"), std::string::npos) << e.what();
  }
  Simulation<float> other_precision(scene.domain, bind(scene.pair), quiet());
  other_precision.add_plane_wall({{0, 0, 0}, {0, 0, 1}, {0, 0, 0}, bind(scene.wall), true, "floor"});
  EXPECT_THROW(other_precision.load_checkpoint(path), SetupError);
  // A truncated file is refused, not read past its end.
  std::filesystem::resize_file(path, std::filesystem::file_size(path) / 2);
  Simulation<double> truncated(scene.domain, bind(scene.pair), quiet());
  truncated.add_plane_wall({{0, 0, 0}, {0, 0, 1}, {0, 0, 0}, bind(scene.wall), true, "floor"});
  EXPECT_THROW(truncated.load_checkpoint(path), SetupError);
  std::filesystem::remove(path);
}

// A checkpoint damaged after it was written is refused, naming the file, before any value of it is
// used: a value edited in place (a position shifted by 1e-7 m, which would resume silently to another
// result) by its checksum, and damage that keeps a valid checksum (a file rewritten by a faulty tool)
// by the checks on every count and index: never a crash, never an index beyond the particles.
TEST(EngineCheckpoint, DamageIsRefusedNamingTheFileNeverResumedNorACrash) {
  const auto path = std::filesystem::temp_directory_path() / fmt::format("engine_ckpt_damage_{}.bin", ::getpid());
  Scene<double> scene;
  auto whole = scene.make();
  whole.run_steps(300);
  whole.save_checkpoint(path);
  const double x0 = whole.arrays().x[0];
  const std::string intact = [&] {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
  }();
  const auto write = [&](const std::string &bytes) { std::ofstream(path, std::ios::binary) << bytes; };
  const auto load = [&] {
    Simulation<double> sim(scene.domain, bind(scene.pair), quiet());
    sim.add_plane_wall({{0, 0, 0}, {0, 0, 1}, {0, 0, 0}, bind(scene.wall), true, "floor"});
    sim.load_checkpoint(path);
  };
  // the first particle's x shifted by 1e-7 m where it is stored
  std::string shifted = intact;
  const auto at = shifted.find(std::string(reinterpret_cast<const char *>(&x0), sizeof x0));
  ASSERT_NE(at, std::string::npos);
  const double moved = x0 + 1e-7;
  std::memcpy(shifted.data() + at, &moved, sizeof moved);
  write(shifted);
  try {
    load();
    FAIL() << "a checkpoint with a shifted position was resumed";
  } catch (const SetupError &e) {
    EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("damaged"), std::string::npos) << e.what();
  }
  // damage under a valid checksum, one byte in every 61: each is refused or read, none crashes
  const std::string payload = intact.substr(0, intact.size() - sizeof(std::uint64_t));
  std::size_t refused = 0, read = 0;
  for (std::size_t i = 20; i < payload.size(); i += 61) {
    std::string damaged = payload;
    damaged[i] = static_cast<char>(~damaged[i]);
    const std::uint64_t sum = checksum(damaged.data(), damaged.size());
    damaged.append(reinterpret_cast<const char *>(&sum), sizeof sum);
    write(damaged);
    try {
      load();
      ++read;
    } catch (const SetupError &) {
      ++refused;
    }
  }
  EXPECT_GT(refused, 0u);
  EXPECT_GT(refused + read, 100u);
  write(intact);
  EXPECT_NO_THROW(load());
  std::filesystem::remove(path);
}

TEST(EngineHistory, SurvivesListRebuilds) {
  // Two spheres pressed together and sheared (no gravity): the tangential spring lives in the list
  // history. Rebuilding the list every step (tiny skin) must give bitwise the same motion as never
  // rebuilding it (huge skin): the history is carried over by particle identity.
  TestSpringDashpot law = TestSpringDashpot::with_restitution(100, 0.5, 0.5);
  auto run = [&](double skin) {
    Settings s = quiet();
    s.gravity = {0, 0, 0};
    s.skin = skin;
    s.dt = 2e-5;
    Simulation<double> sim({{0, 0, 0}, {0.02, 0.02, 0.02}, {true, true, true}}, bind(law), s);
    ParticleSet p;
    push_particle(p, 0.0095, 0.01, 0.01, 0.0005, 0.001, 0.02, 0);
    push_particle(p, 0.01049, 0.01, 0.01, 0.0005, -0.001, -0.02, 0);
    sim.add_particles(p, 2500);
    sim.run_steps(200);
    return sim;
  };
  const auto rebuilt = run(1e-9), kept = run(0.004);
  EXPECT_GT(rebuilt.counters().list_builds, 150u);
  EXPECT_EQ(kept.counters().list_builds, 1u);
  EXPECT_TRUE(same_state(rebuilt, kept));
}

// The step profile accounts for every second of step(): its parts are not negative, add up to the
// counters' wall time (to rounding), and a scene of touching spheres spends time on pairs and lists.
TEST(EngineCounters, TheStepProfileAddsUpToTheWallTime) {
  Scene<double> scene;
  auto sim = scene.make();
  sim.run_steps(600);
  const auto &c = sim.counters();
  const auto &p = c.profile;
  for (double part : {p.integrate, p.neighbours, p.pairs, p.planes, p.geometries}) EXPECT_GE(part, 0.0);
  EXPECT_GT(p.pairs, 0.0);
  EXPECT_GT(p.neighbours, 0.0);
  EXPECT_GT(p.other, -1e-9 * c.wall_seconds);  // the rest, by difference: rounding only
  EXPECT_NEAR(p.total(), c.wall_seconds, 1e-9 * c.wall_seconds);
}
