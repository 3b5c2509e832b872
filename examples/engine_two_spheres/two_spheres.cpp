// Two spheres approach head-on, collide once under contact/hooke_slider and fly apart. Prints the
// velocities before and after, the coefficient of restitution and the total momentum. The law is set
// to restitution 0.5; without a clamp on the normal force its isolated collision rebounds with
// exactly that, up to the time discretisation (docs/engine.md). Everything in SI units.
#include <engine/plugin_law.hpp>
#include <engine/simulation.hpp>

#include <cstdio>
#include <exception>
#include <stdexcept>
#include <string>

namespace engine = spreadmap::engine;

namespace {

struct Sphere {
  double x, vx, radius, mass;
};

// Particle `id` of the current state (the engine keeps particles in its own order).
Sphere sphere(const engine::Simulation<double> &sim, std::uint32_t id) {
  const engine::ParticleSet s = sim.state();
  for (std::size_t i = 0; i < s.size(); ++i)
    if (s.id[i] == id) return {s.x[i], s.vx[i], s.radius[i], s.mass[i]};
  throw std::runtime_error("particle " + std::to_string(id) + " left the domain");
}

double momentum(const Sphere &a, const Sphere &b) { return a.mass * a.vx + b.mass * b.vx; }

}  // namespace

int main() try {
  const double restitution = 0.5;
  // Stiffness from the impact speed that gives the maximum overlap: K_n = m_eq (v_max / overlap_max)^2.
  const auto law = engine::load_contact_law(
      "hooke_slider", {{"restitution", restitution}, {"v_max", "1 m/s"}, {"overlap_max", "5 um"}, {"friction", 0.3}});

  engine::Domain domain;  // a 10 mm box, open on every side
  domain.lo = {-5e-3, -5e-3, -5e-3};
  domain.hi = {5e-3, 5e-3, 5e-3};
  engine::Settings settings;
  settings.gravity = {0, 0, 0};
  // A step of 0.005 x the stability limit, about 330 steps per contact: the restitution's discretisation
  // error is first order in the step (docs/engine.md).
  settings.dt_safety = 0.005;
  settings.log = [](const std::string &message) { std::fprintf(stderr, "%s\n", message.c_str()); };
  engine::Simulation<double> sim(domain, law.law(), settings);

  // Sphere 0: 1 mm radius at x = -1.05 mm moving at +0.25 m/s; sphere 1: 0.75 mm radius at
  // x = 0.75 mm moving at -0.15 m/s. 50 um apart, closing at 0.4 m/s. Titanium, 4430 kg/m^3.
  engine::ParticleSet set;
  set.x = {-1.05e-3, 0.75e-3};
  set.y = {0, 0};
  set.z = {0, 0};
  set.vx = {0.25, -0.15};
  set.vy = {0, 0};
  set.vz = {0, 0};
  set.radius = {1e-3, 0.75e-3};
  set.id = {0, 1};
  sim.add_particles(set, 4430);

  const Sphere a0 = sphere(sim, 0), b0 = sphere(sim, 1);
  // Step until the spheres have touched and are apart again; after that nothing changes their speed.
  bool touched = false;
  for (;;) {
    sim.step();
    const Sphere a = sphere(sim, 0), b = sphere(sim, 1);
    const double gap = (b.x - a.x) - (a.radius + b.radius);
    if (gap < 0) touched = true;
    else if (touched) break;
    if (sim.time() > 1e-2) throw std::runtime_error("the spheres never separated");
  }
  const Sphere a1 = sphere(sim, 0), b1 = sphere(sim, 1);
  const double measured = -(b1.vx - a1.vx) / (b0.vx - a0.vx);

  std::printf("law: %s from %s\n", law.id().c_str(), law.file().c_str());
  std::printf("parameters (SI): %s\n", law.params().dump().c_str());
  std::printf("time step: %.6g s, %llu steps to %.6g s\n", sim.dt(), static_cast<unsigned long long>(sim.step_count()),
              sim.time());
  std::printf("before: v0 = %.17g m/s, v1 = %.17g m/s\n", a0.vx, b0.vx);
  std::printf("after: v0 = %.17g m/s, v1 = %.17g m/s\n", a1.vx, b1.vx);
  std::printf("restitution: %.17g (set %.17g)\n", measured, restitution);
  std::printf("momentum: before %.17g kg m/s, after %.17g kg m/s\n", momentum(a0, b0), momentum(a1, b1));
  return 0;
} catch (const std::exception &e) {
  std::fprintf(stderr, "%s\n", e.what());
  return 1;
}
