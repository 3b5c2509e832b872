// The engine's fast paths give exactly the results of the plain ones: a law without history, or whose
// history mirrors, evaluated once per pair (engine/pair_loops.hpp) against every list entry, for any number of
// threads, with every instruction set the processor runs; planes evaluated in place against a gathered copy of the
// touching particles; a geometry evaluated for its near particles only against every particle; sleeping particles
// (Settings::sleep): no bit changes where none may sleep, asleep means exactly still, woken by impacts.
#include "engine_test_law.hpp"

#include <engine/errors.hpp>
#include <spreadmap/contact_parts.hpp>
#include <spreadmap/simd.hpp>

#include <cstring>
#include <filesystem>
#include <limits>
#include <gtest/gtest.h>
#include <memory>
#include <omp.h>
#include <string>
#include <unistd.h>

namespace sm = spreadmap;
using namespace sm::engine;
using namespace sm::engine::testing;

namespace {

// Spring-dashpot normal force, viscous-regularised Coulomb slider and a rolling torque: no history,
// force and torque on both sides of a contact, as the study's law (hooke_slider) has them.
struct TestSlider {
  static constexpr int history = 0;
  double k = 100, zeta = 0.2, mu = 0.4, gamma = 200, mu_r = 0.05;

  double natural_frequency(double m_eq, double) const { return std::sqrt(k / m_eq); }
  double damping_ratio(double, double) const { return zeta; }
  bool makes_torque() const { return true; }

  template <class Real> SM_HD sm::ContactForce<Real> operator()(const sm::ContactState<Real> &c, Real *) const {
    sm::ContactForce<Real> f;
    f.normal = Real(k) * c.overlap - Real(2 * zeta) * std::sqrt(Real(k) * c.m_eq) * c.v_n;
    const Real fn = f.normal < 0 ? -f.normal : f.normal;
    // selects, no branch, as hooke_slider: evaluate_pairs runs it on SIMD lanes
    const Real slip = sm::norm(c.v_t);
    const Real slide = -sm::min(Real(mu) * fn, c.m_eq * Real(gamma) * slip) / slip;
    f.tangent = {slip > 0 ? c.v_t.x * slide : 0, slip > 0 ? c.v_t.y * slide : 0, slip > 0 ? c.v_t.z * slide : 0};
    const sm::Vec3<Real> roll = c.w_rel - c.normal * sm::dot(c.w_rel, c.normal);
    const Real spin = sm::norm(roll);
    const Real resist = -Real(mu_r) * c.r_eff * fn / spin;
    f.torque = {spin > 0 ? roll.x * resist : 0, spin > 0 ? roll.y * resist : 0, spin > 0 ? roll.z * resist : 0};
    return f;
  }
};

// Spring-dashpot normal force and a Cundall-Strack tangential spring with Coulomb cap: 3 values of
// history per contact, the spring's elongation, which seen from the other body is its negation.
struct TestSpring {
  static constexpr int history = 3;
  static constexpr bool history_mirrors = true;
  double k = 100, zeta = 0.2, mu = 0.4, k_t = 30;

  double natural_frequency(double m_eq, double) const { return std::sqrt(std::max(k, 3.5 * k_t) / m_eq); }
  double damping_ratio(double, double) const { return zeta; }
  bool makes_torque() const { return true; }

  template <class Real> SM_HD sm::ContactForce<Real> operator()(const sm::ContactState<Real> &c, Real *hist) const {
    sm::ContactForce<Real> f;
    f.normal = Real(k) * c.overlap - Real(2 * zeta) * std::sqrt(Real(k) * c.m_eq) * c.v_n;
    const Real fn = f.normal < 0 ? -f.normal : f.normal;
    const Real damping = Real(2 * zeta) * std::sqrt(Real(k_t) * Real(2.0 / 7.0) * c.m_eq);
    f.tangent = sm::tangential_spring(c.normal, c.v_t, Real(k_t), damping, Real(mu) * fn, c.dt, hist);
    return f;
  }
};

template <class Law> ContactLaw bind_law(const Law &law) { return {&sm::detail::ContactOps<Law>::table, &law}; }

// A ball of radius R moving at constant velocity: a geometry with a bound on its speed.
struct TestBall {
  double centre[3], velocity[3], radius;

  template <class Real> SM_HD bool operator()(const sm::Vec3<Real> &p, Real r, Real t, sm::WallHit<Real> &hit) const {
    const sm::Vec3<Real> c{Real(centre[0] + velocity[0] * t), Real(centre[1] + velocity[1] * t),
                           Real(centre[2] + velocity[2] * t)};
    const sm::Vec3<Real> d = p - c;
    const Real dist = sm::norm(d);
    hit.overlap = r - (dist - Real(radius));
    if (!(hit.overlap > 0) || !(dist > 0)) return false;
    hit.normal = d * (Real(1) / dist);
    hit.velocity = {Real(velocity[0]), Real(velocity[1]), Real(velocity[2])};
    return true;
  }
  double max_surface_speed() const {
    return std::sqrt(velocity[0] * velocity[0] + velocity[1] * velocity[1] + velocity[2] * velocity[2]);
  }
  void describe(sm::sm_spreader_description_v2 *) const {}
  void pose(double, sm::sm_spreader_pose_v2 *) const {}
};

template <class Real> bool same_bits(const std::vector<Real> &a, const std::vector<Real> &b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(Real)) == 0;
}

// Positions, velocities and spins in id order.
bool same_state(const Simulation<double> &a, const Simulation<double> &b) {
  const ParticleSet p = a.state(), q = b.state();
  auto by_id = [](const ParticleSet &s, const std::vector<double> &c) {
    std::vector<double> out(c.size());
    for (std::size_t i = 0; i < c.size(); ++i) out[s.id[i]] = c[i];
    return out;
  };
  for (auto m : {&ParticleSet::x, &ParticleSet::y, &ParticleSet::z, &ParticleSet::vx, &ParticleSet::vy,
                 &ParticleSet::vz, &ParticleSet::wx, &ParticleSet::wy, &ParticleSet::wz})
    if (!same_bits(by_id(p, p.*m), by_id(q, q.*m))) return false;
  return a.size() == b.size() && a.time() == b.time();
}

Settings quiet() {
  Settings s;
  s.log = [](const std::string &) {};
  s.parallel_min_particles = 0;  // every thread, even for this small scene
  return s;
}

// Polydisperse spheres falling into a periodic box onto a floor, with friction (and, for the slider,
// rolling resistance): many contacts, several list builds.
template <class Law> struct SceneOf {
  Law pair, wall;
  Domain domain{{0, 0, 0}, {0.012, 0.012, 0.05}, {true, true, false}};
  SceneOf(Law pair, Law wall) : pair(pair), wall(wall) {}
  std::unique_ptr<Simulation<double>> make(Settings settings, std::size_t n = 1500) {
    auto sim = std::make_unique<Simulation<double>>(domain, bind_law(pair), settings);
    sim->add_plane_wall({{0, 0, 0}, {0, 0, 1}, {0, 0, 0}, bind_law(wall), true, "floor"});
    sim->add_particles(random_lattice(n, 0.0005, {0, 0, 0.0006}, {0.012, 0.012, 0.045}, 0.3), 2500);
    return sim;
  }
  // `steps` steps on `threads` threads with one switch of the settings set to `on`.
  std::unique_ptr<Simulation<double>> run(bool Settings::*option, bool on, int threads, std::uint64_t steps) {
    omp_set_num_threads(threads);
    Settings s = quiet();
    s.*option = on;
    auto sim = make(s);
    sim->run_steps(steps);
    omp_set_num_threads(2);
    return sim;
  }
};
struct Scene : SceneOf<TestSlider> {
  Scene() : SceneOf({}, {200, 0.2, 0.3, 200, 0.05}) {}
};
struct SpringScene : SceneOf<TestSpring> {
  SpringScene() : SceneOf({}, {200, 0.2, 0.3, 60}) {}
};

template <class AnyScene> void expect_pairs_once_same_bits_as_every_entry() {
  AnyScene scene;
  ASSERT_TRUE(law_pairs_once(bind_law(scene.pair)));
  auto run = [&](bool on, int threads) { return scene.run(&Settings::pairs_once, on, threads, 800); };
  const auto every = run(false, 2), one = run(true, 1), two = run(true, 2), three = run(true, 3);
  EXPECT_GT(every->counters().list_builds, 3u) << "the scene should rebuild its list several times";
  EXPECT_TRUE(same_state(*every, *one)) << "evaluating each pair once changes the result";
  EXPECT_TRUE(same_state(*one, *two)) << "1 vs 2 threads differ";
  EXPECT_TRUE(same_state(*one, *three)) << "1 vs 3 threads differ";
}

}  // namespace

TEST(EnginePairsOnce, SameBitsAsEveryEntryForAnyThreadCount) { expect_pairs_once_same_bits_as_every_entry<Scene>(); }

// The tangential spring's history, kept on the pair's entry (i, j) and mirrored to (j, i), gives the
// bits of each entry evolving its own, through contacts that form, slide, part and move between threads.
TEST(EnginePairsOnce, ALawWhoseHistoryMirrorsGivesTheSameBitsAsEveryEntry) {
  expect_pairs_once_same_bits_as_every_entry<SpringScene>();
}

// A team larger than PairBalance::max_threads: the pair loop splits the entries equally and each
// thread sums its own waiting particles' records (the branch no tuned team takes). About 20
// particles a thread, so most of them wait for records.
TEST(EnginePairsOnce, SameBitsOnATeamLargerThanTheBalanceTunes) {
  Scene scene;
  const int many = PairBalance::max_threads + 3;
  auto run = [&](int threads) { return scene.run(&Settings::pairs_once, true, threads, 150); };
  const auto one = run(1), crowd = run(many);
  EXPECT_TRUE(same_state(*one, *crowd)) << "1 vs " << many << " threads differ";
}

// The pair and wall queues, the kicks and the plane overlaps compiled for plain x86-64, AVX2 and
// AVX-512 (those the processor runs): the same IEEE operations in the same order on any lane width.
template <class AnyScene> void expect_every_instruction_set_same_bits() {
  AnyScene scene;
  const sm::SimdLevel in_use = sm::simd_level();
  auto run = [&](sm::SimdLevel level, int threads) {
    EXPECT_EQ(sm::set_simd_level(level), level);
    return scene.run(&Settings::pairs_once, true, threads, 800);
  };
  const auto base = run(sm::SimdLevel::base, 1);
  for (auto level : {sm::SimdLevel::avx2, sm::SimdLevel::avx512}) {
    if (level > sm::simd_supported()) continue;  // this processor does not run it
    for (int threads : {1, 2})
      EXPECT_TRUE(same_state(*base, *run(level, threads))) << sm::simd_name(level) << " on " << threads << " threads";
  }
  sm::set_simd_level(in_use);
}

TEST(EngineSimd, EveryInstructionSetGivesTheSameBits) { expect_every_instruction_set_same_bits<Scene>(); }
TEST(EngineSimd, EveryInstructionSetGivesTheSameBitsWithMirroredHistory) {
  expect_every_instruction_set_same_bits<SpringScene>();
}

template <class AnyScene> void expect_resume_bitwise_identical() {
  const auto path = std::filesystem::temp_directory_path() / ("engine_once_" + std::to_string(::getpid()) + ".bin");
  AnyScene scene;
  auto whole = scene.make(quiet());
  whole->run_steps(300);
  whole->save_checkpoint(path);
  whole->run_steps(300);
  auto resumed = std::make_unique<Simulation<double>>(scene.domain, bind_law(scene.pair), quiet());
  resumed->add_plane_wall({{0, 0, 0}, {0, 0, 1}, {0, 0, 0}, bind_law(scene.wall), true, "floor"});
  resumed->load_checkpoint(path);
  resumed->run_steps(300);
  std::filesystem::remove(path);
  EXPECT_TRUE(same_state(*whole, *resumed));
}

TEST(EnginePairsOnce, ResumeIsBitwiseIdentical) { expect_resume_bitwise_identical<Scene>(); }
TEST(EnginePairsOnce, ResumeIsBitwiseIdenticalWithMirroredHistory) { expect_resume_bitwise_identical<SpringScene>(); }

TEST(EnginePlanes, InPlaceGivesTheSameBitsAsTheGatheredCopyForAnyThreadCount) {
  // The falling packing lands on the floor: many particles touch it, some leave it again.
  Scene scene;
  auto run = [&](bool on, int threads) { return scene.run(&Settings::planes_in_place, on, threads, 1500); };
  const auto gathered = run(false, 1), one = run(true, 1), two = run(true, 2);
  std::size_t on_floor = 0;
  for (std::size_t i = 0; i < one->size(); ++i) on_floor += one->arrays().z[i] < one->arrays().r[i] ? 1u : 0u;
  EXPECT_GT(on_floor, 50u) << "the packing should have reached the floor";
  EXPECT_TRUE(same_state(*gathered, *one)) << "in place and gathered differ";
  EXPECT_TRUE(same_state(*one, *two)) << "1 vs 2 threads differ";
}

TEST(EngineGeometry, NearParticlesOnlyGiveTheSameBitsAsEveryParticle) {
  // A ball comes down into the falling packing. Without a speed bound the engine evaluates the
  // geometry for every particle; with it, only for those near the ball.
  Scene scene;
  const TestBall ball{{0.006, 0.006, 0.03}, {0.02, 0.01, -0.3}, 0.003};
  sm::sm_spreader_ops_v2 unbounded = sm::detail::GeometryOps<TestBall>::table;
  unbounded.max_surface_speed = nullptr;
  // The near particles' forces are evaluated inside the pair loop's run, each thread for the particles
  // whose pair forces it sums, and added after the floor's (in that run too, or after the floor's own).
  auto run = [&](const sm::sm_spreader_ops_v2 *ops, int threads = 2, bool pairs_once = true,
                 bool planes_in_place = true) {
    omp_set_num_threads(threads);
    Settings settings = quiet();
    settings.pairs_once = pairs_once;
    settings.planes_in_place = planes_in_place;
    auto sim = scene.make(settings);
    if (ops) sim->add_geometry({ops, &ball, bind_law(scene.wall), "ball"});
    sim->run_steps(1500);
    omp_set_num_threads(2);
    return sim;
  };
  const auto *bounded = &sm::detail::GeometryOps<TestBall>::table;
  const auto every = run(&unbounded), none = run(nullptr);
  EXPECT_FALSE(same_state(*every, *none)) << "the ball should have pushed particles";
  for (int threads : {1, 2, 3}) {
    EXPECT_TRUE(same_state(*run(bounded, threads), *every)) << threads << " threads";
    EXPECT_TRUE(same_state(*run(bounded, threads, false), *every)) << threads << " threads, every list entry";
    EXPECT_TRUE(same_state(*run(bounded, threads, true, false), *every)) << threads << " threads, floor gathered";
  }
}

TEST(EngineGeometry, ItsForcesFollowTheFloorsOnParticlesThatTouchBoth) {
  // A ball rising through the floor under the landing packing: particles pressed between the two get
  // the floor's force and the ball's in that order, whichever path evaluates them.
  Scene scene;
  const TestBall ball{{0.006, 0.006, -0.0035}, {0, 0, 0.1}, 0.003};
  sm::sm_spreader_ops_v2 unbounded = sm::detail::GeometryOps<TestBall>::table;
  unbounded.max_surface_speed = nullptr;
  std::size_t pressed = 0;  // particle-steps touching the floor and the ball at once (every 10 steps)
  auto count_pressed = [&](const Simulation<double> &sim) {
    const auto &a = sim.arrays();
    const double cz = ball.centre[2] + ball.velocity[2] * sim.time();
    for (std::size_t i = 0; i < sim.size(); ++i) {
      const double dx = a.x[i] - ball.centre[0], dy = a.y[i] - ball.centre[1], dz = a.z[i] - cz;
      pressed += a.z[i] < a.r[i] && std::sqrt(dx * dx + dy * dy + dz * dz) < ball.radius + a.r[i] ? 1u : 0u;
    }
    return true;
  };
  auto run = [&](const sm::sm_spreader_ops_v2 *ops, int threads, bool count) {
    omp_set_num_threads(threads);
    auto sim = scene.make(quiet());
    sim->add_geometry({ops, &ball, bind_law(scene.wall), "ball"});
    const double t_end = 2500 * sim->dt();
    if (count) sim->run_until(t_end, count_pressed, 10);
    else sim->run_until(t_end);
    omp_set_num_threads(2);
    return sim;
  };
  const auto every = run(&unbounded, 1, true);
  EXPECT_GT(pressed, 20u) << "some particles should touch the floor and the ball at once";
  for (int threads : {1, 2})
    EXPECT_TRUE(same_state(*run(&sm::detail::GeometryOps<TestBall>::table, threads, false), *every))
        << threads << " threads";
}

namespace {

// The falling packing of Scene, smaller, left to come to rest; then particles may sleep everywhere.
struct RestingHeap {
  Scene scene;
  Settings settings = quiet();
  std::unique_ptr<Simulation<double>> sim;
  explicit RestingHeap(std::size_t n = 200) {
    settings.sleep = true;
    settings.sleep_checks = 3;
    settings.sleep_speed = 2e-3;
    settings.parallel_min_particles = 2000;  // one thread: small and quick, also under the sanitizers
    sim = scene.make(settings, n);
    sim->run_until(0.25);  // fallen and at rest (damping time 1 / (zeta omega) ~ 0.4 ms)
  }
};

double top_of(const Simulation<double> &sim) {
  double top = 0;
  for (std::size_t i = 0; i < sim.size(); ++i) top = std::max(top, double(sim.arrays().z[i] + sim.arrays().r[i]));
  return top;
}

}  // namespace

TEST(EngineSleep, WhereNoneMaySleepNoBitChanges) {
  // sleep on, but no region given: the same numbers as without sleeping, for any thread count
  Scene scene;
  auto run = [&](bool on, int threads) { return scene.run(&Settings::sleep, on, threads, 800); };
  const auto plain = run(false, 2), one = run(true, 1), two = run(true, 2);
  EXPECT_TRUE(same_state(*plain, *one));
  EXPECT_TRUE(same_state(*one, *two));
  EXPECT_EQ(one->sleeping_count(), 0u);
}

TEST(EngineSleep, ARestingHeapSleepsStaysExactlyPutAndLeavesTheList) {
  RestingHeap heap;
  auto &sim = *heap.sim;
  const std::size_t entries_awake = sim.list_entries();
  sim.set_sleep_region(1.0);  // the whole box
  sim.run_steps(2000);
  EXPECT_GT(sim.sleeping_count(), sim.size() * 9 / 10) << "a heap at rest should fall asleep";
  EXPECT_LT(sim.list_entries(), entries_awake / 2) << "pairs of two sleeping spheres stay listed";
  // asleep: not integrated; positions keep every bit, velocities are exactly zero
  const ParticleSet before = sim.state();
  const double integrated = sim.counters().integrated_particle_steps, all = sim.counters().particle_steps;
  sim.run_steps(1000);
  const ParticleSet after = sim.state();
  std::size_t frozen = 0;
  for (std::size_t i = 0; i < after.size(); ++i) {
    if (sim.arrays().mobile[i] != 0) continue;
    std::size_t k = 0;
    while (before.id[k] != after.id[i]) ++k;
    frozen += before.x[k] == after.x[i] && before.y[k] == after.y[i] && before.z[k] == after.z[i] && after.vx[i] == 0 &&
              after.vy[i] == 0 && after.vz[i] == 0 && after.wx[i] == 0;
  }
  EXPECT_EQ(frozen, sim.sleeping_count());
  const double integrated_share =
      (sim.counters().integrated_particle_steps - integrated) / (sim.counters().particle_steps - all);
  EXPECT_LT(integrated_share, 0.1);
}

TEST(EngineSleep, BelowADepthBoundOnlyTheBuriedSpheresSleep) {
  // No x region (-infinity): only spheres whose centre lies below half the heap's height may sleep.
  RestingHeap heap;
  auto &sim = *heap.sim;
  const double bound = 0.5 * top_of(sim);
  std::size_t below = 0;
  for (std::size_t i = 0; i < sim.size(); ++i) below += sim.arrays().z[i] < bound;
  sim.set_sleep_region(-std::numeric_limits<double>::infinity(), bound);
  sim.run_steps(2000);
  std::size_t asleep_above = 0;
  for (std::size_t i = 0; i < sim.size(); ++i)
    asleep_above += sim.arrays().mobile[i] == 0 && sim.arrays().z[i] >= bound;
  std::printf("%zu of the %zu spheres below z = %.3g mm sleep, %zu above\n", sim.sleeping_count(), below, bound * 1e3,
              asleep_above);
  EXPECT_EQ(asleep_above, 0u) << "a sphere above the bound fell asleep";
  EXPECT_GT(sim.sleeping_count(), below * 9 / 10) << "the buried spheres at rest should sleep";
  EXPECT_LE(sim.sleeping_count(), below);
}

TEST(EngineSleep, ASphereDroppedOnTheSleepingHeapWakesItAndDoesNotFallThrough) {
  RestingHeap heap;
  auto &sim = *heap.sim;
  sim.set_sleep_region(1.0);
  sim.run_steps(2000);
  const std::size_t asleep = sim.sleeping_count();
  ASSERT_GT(asleep, sim.size() / 2);
  const double top = top_of(sim);
  ParticleSet drop;
  push_particle(drop, 0.006, 0.006, top + 0.002, 0.0006, 0, 0, -0.5);
  sim.add_particles(drop, 2500);
  sim.set_sleep_region(-1.0);  // nothing falls asleep again: what wakes stays awake
  sim.run_steps(1500);
  EXPECT_LT(sim.sleeping_count(), asleep) << "the impact woke nobody";
  double z = 0;
  for (std::size_t i = 0; i < sim.size(); ++i)
    if (sim.arrays().id[i] == sim.size() - 1) z = sim.arrays().z[i];
  EXPECT_GT(z, top - 0.0015) << "the dropped sphere sank through the sleeping heap";
}

TEST(EngineSleep, ResumeIsBitwiseIdentical) {
  const auto path = std::filesystem::temp_directory_path() / ("engine_sleep_" + std::to_string(::getpid()) + ".bin");
  RestingHeap heap(150);
  auto &whole = *heap.sim;
  whole.set_sleep_region(0.006, 0.002);  // half the box, and the spheres below 2 mm
  whole.run_steps(700);
  whole.save_checkpoint(path);
  whole.run_steps(700);
  Simulation<double> resumed(heap.scene.domain, bind_law(heap.scene.pair), heap.settings);
  resumed.add_plane_wall({{0, 0, 0}, {0, 0, 1}, {0, 0, 0}, bind_law(heap.scene.wall), true, "floor"});
  resumed.load_checkpoint(path);
  resumed.run_steps(700);
  std::filesystem::remove(path);
  EXPECT_GT(whole.sleeping_count(), 0u);
  EXPECT_EQ(whole.sleeping_count(), resumed.sleeping_count());
  EXPECT_TRUE(same_state(whole, resumed));
}

TEST(EngineSleep, ALawWithHistoryIsRefused) {
  TestSpringDashpot law = TestSpringDashpot::with_restitution(100, 0.5, 0.3);  // tangential springs: history
  Settings s = quiet();
  s.sleep = true;
  try {
    Simulation<double> sim(Domain{{0, 0, 0}, {0.01, 0.01, 0.01}, {false, false, false}}, bind(law), s);
    FAIL() << "sleep with a history law was accepted";
  } catch (const SetupError &e) {
    EXPECT_NE(std::string(e.what()).find("without history"), std::string::npos) << e.what();
  }
}
