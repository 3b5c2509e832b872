// bench_engine: engine throughput in particle-steps per second on a granular box: ~20,000 spheres of
// 250 um (Ti-6Al-4V, 4430 kg/m^3) in a 5 mm x 5 mm periodic box on a floor, first settling, then
// shaken by the floor (50 um amplitude at 100 Hz). Contact law: contact/hooke_slider (the study's
// model, V_max = 0.5 m/s, Delta_max = 2.5 um, e = 0.8, mu = 0.185 / 0.25) when its header is in the
// tree, else the engine tests' linear spring-dashpot. dt = 7.5e-7 s as the LIGGGHTS peer runs.
// Measured for double and float, 1 and 2 threads.
//
// Usage: bench_engine [particles=20000] [steps=1000]
#include <engine/simulation.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <memory>
#include <numbers>
#include <omp.h>
#include <random>
#include <string>
#include <thread>

#if __has_include(<plugins/contact/hooke_slider/hooke_slider.hpp>)
#include <plugins/contact/hooke_slider/hooke_slider.hpp>
#define BENCH_LAW "contact/hooke_slider"
#else
#include "../tests/unit/engine_test_law.hpp"
#define BENCH_LAW "engine test law (linear spring-dashpot + tangential spring)"
#endif

namespace sm = spreadmap;
using namespace sm::engine;

namespace {

constexpr double radius = 125e-6, density = 4430, box = 5e-3, dt = 7.5e-7;

#if __has_include(<plugins/contact/hooke_slider/hooke_slider.hpp>)
using Law = sm::HookeSlider;
Law make_law(double friction) {
  nlohmann::json j;
  for (const auto &p : Law::params) {
    if (p.type == SM_ENUM || p.type == SM_STRING) j[p.name] = p.def_text ? p.def_text : "";
    else if (p.type == SM_BOOLEAN) j[p.name] = p.def != 0;
    else j[p.name] = p.def;
  }
  j["v_max"] = 0.5;
  j["overlap_max"] = 2.5e-6;
  j["restitution"] = 0.8;
  j["friction"] = friction;
  return Law::bind(sm::Values(j));
}
#else
using Law = sm::engine::testing::TestSpringDashpot;
Law make_law(double friction) {
  const double m = density * 4.0 / 3.0 * std::numbers::pi * std::pow(radius, 3);
  return Law::with_restitution(0.5 * m * std::pow(0.5 / 2.5e-6, 2), 0.8, friction);
}
#endif

std::string cpu_model() {
  std::ifstream in("/proc/cpuinfo");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind("model name", 0) == 0) return line.substr(line.find(':') + 2);
  return "unknown";
}

ParticleSet initial_packing(std::size_t n) {
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<double> u(-1, 1);
  const double pitch = 2.1 * radius;
  const int per_row = int(box / pitch);
  ParticleSet s;
  for (std::size_t k = 0; k < n; ++k) {
    const int ix = int(k % per_row), iy = int((k / per_row) % per_row), iz = int(k / (per_row * per_row));
    s.x.push_back((ix + 0.5) * pitch + 0.02 * radius * u(rng));
    s.y.push_back((iy + 0.5) * pitch + 0.02 * radius * u(rng));
    s.z.push_back(radius * 1.05 + iz * pitch + 0.02 * radius * u(rng));
    s.radius.push_back(radius);
    s.vx.push_back(0.05 * u(rng));
    s.vy.push_back(0.05 * u(rng));
    s.vz.push_back(0.05 * u(rng));
  }
  return s;
}

struct Scene {
  Law pair = make_law(0.185), floor = make_law(0.25);
  Domain domain{{0, 0, -1e-3}, {box, box, 0.05}, {true, true, false}};

  template <class Real> std::unique_ptr<Simulation<Real>> make(const ParticleSet &particles) {
    Settings s;
    s.dt = dt;
    s.log = [](const std::string &) {};
    auto sim = std::make_unique<Simulation<Real>>(domain, ContactLaw{&sm::detail::ContactOps<Law>::table, &pair}, s);
    sim->add_plane_wall(
        {{0, 0, 0}, {0, 0, 1}, {0, 0, 0}, {&sm::detail::ContactOps<Law>::table, &floor}, true, "floor"});
    sim->add_particles(particles, density);
    return sim;
  }
};

// Floor oscillation z = A sin(2 pi f t): its velocity is set each step.
template <class Real> void shake(Simulation<Real> &sim, std::uint64_t steps) {
  constexpr double amplitude = 50e-6, frequency = 100;
  for (std::uint64_t k = 0; k < steps; ++k) {
    const double w = 2 * std::numbers::pi * frequency;
    sim.set_plane_wall_velocity(0, {0, 0, amplitude * w * std::cos(w * sim.time())});
    sim.step();
  }
}

template <class Real>
void measure(Scene &scene, const ParticleSet &settled, int threads, std::uint64_t steps, const char *name) {
  omp_set_num_threads(threads);
  auto sim = scene.make<Real>(settled);
  sim->run_steps(50);  // warm-up: first list, caches, memory
  const RunCounters before = sim->counters();
  shake(*sim, steps);
  const RunCounters &after = sim->counters();
  const double ps = (after.particle_steps - before.particle_steps) / (after.wall_seconds - before.wall_seconds);
  std::printf(
      "%-7s %d thread%s  %10.3g particle-steps/s  (%.0f ns per particle-step; %zu particles, %.2f neighbours "
      "per particle (full list), %llu list builds in %llu steps)\n",
      name, threads, threads > 1 ? "s" : " ", ps, 1e9 / ps, sim->size(),
      double(sim->list_entries()) / double(sim->size()),
      static_cast<unsigned long long>(after.list_builds - before.list_builds), static_cast<unsigned long long>(steps));
}

}  // namespace

int main(int argc, char **argv) {
  const std::size_t n = argc > 1 ? std::strtoul(argv[1], nullptr, 10) : 20000;
  const std::uint64_t steps = argc > 2 ? std::strtoull(argv[2], nullptr, 10) : 1000;
  std::printf("bench_engine: %zu spheres of %.0f um, contact law %s, dt = %.3g s\n", n, 2e6 * radius, BENCH_LAW, dt);
  std::printf("machine: %s, %u hardware threads (OpenMP sees %d processors); instruction set %s\n", cpu_model().c_str(),
              std::thread::hardware_concurrency(), omp_get_num_procs(), spreadmap::simd_name(spreadmap::simd_level()));

  Scene scene;
  // Settle (not timed as a figure): the packing falls and collapses onto the floor.
  omp_set_num_threads(std::min(2, omp_get_num_procs()));
  auto settling = scene.make<double>(initial_packing(n));
  const auto t0 = std::chrono::steady_clock::now();
  settling->run_steps(4000);
  std::printf("settling: 4000 steps in %.1f s (%.3g particle-steps/s)\n",
              std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(),
              settling->counters().particle_steps_per_second());
  const ParticleSet settled = settling->state();

  measure<double>(scene, settled, 1, steps, "double");
  measure<double>(scene, settled, 2, steps, "double");
  measure<float>(scene, settled, 1, steps, "float");
  measure<float>(scene, settled, 2, steps, "float");
  return 0;
}
