// Small spreading scenes for the stability suite, built on the engine API with the real plugins'
// code (hooke_slider and roller, compiled in from their headers, bound from their schema defaults
// plus overrides, exactly as the host binds them): a few hundred 250 um spheres on a periodic strip,
// a roller behind them, the quick preset's materials. Every knob the suite turns is a field of
// SceneSpec; everything else keeps the quick preset's value.
#pragma once
#include <engine/simulation.hpp>

#include <array>
#include <memory>
#include <optional>
#include <string>

#include "plugins/contact/hooke_slider/hooke_slider.hpp"
#include "plugins/spreader/roller/roller.hpp"

namespace spreadmap::extremes {

struct Material {
  double restitution = 0.8;
  double friction = 0.185;
};

struct SceneSpec {
  // Powder: `count` spheres on a jittered lattice, `layers` deep, starting at x = heap_from.
  std::size_t count = 150;
  std::size_t layers = 3;
  double diameter = 250e-6, density = 4430;
  double heap_from = 8.5e-3;  // clear of the roller's front at rest (axis x = 6 mm, gap 0.5 mm)
  double drop = 0;            // extra height of the whole lattice above the substrate [m]
  double jitter_speed = 0;    // random initial speeds up to this [m/s] (fixed seed)
  double fall_speed = 0;      // initial downward speed of every sphere [m/s]
  // Box: x open (particles leaving are removed and counted), y periodic, z open.
  double length = 30e-3, width = 1.25e-3, height = 12e-3;
  bool end_walls = false;  // plane walls at x = 0 and x = length (a closed box along x)
  // Contacts: hooke_slider everywhere, as in the quick preset.
  double v_max = 0.5, overlap_max = 5e-6;
  Material particles{0.8, 0.185}, substrate{0.8, 0.25}, spreader_surface{0.8, 0.12};
  // Roller (no roller when U = 0).
  double U = 0.1, omega = 0, gap = 0.5e-3, roller_diameter = 10e-3, start = 6e-3, travel = 8e-3;
  // Time.
  double dt = 0, dt_safety = 0.4;
  bool allow_unstable_dt = false;
  double gravity = 9.81;
};

// One scene: the bound laws and geometry live here, at fixed addresses, for the simulation's life.
class Scene {
 public:
  explicit Scene(const SceneSpec &spec);
  Scene(const Scene &) = delete;
  Scene &operator=(const Scene &) = delete;

  engine::Simulation<double> &sim() { return *sim_; }
  const engine::Simulation<double> &sim() const { return *sim_; }
  const SceneSpec &spec() const { return spec_; }
  bool has_roller() const { return roller_.has_value(); }
  const spreader::Roller &roller() const { return *roller_; }
  // Seconds until the roller stops (0 without one).
  double spreading_time() const { return roller_ ? roller_->body.travel.duration : 0.0; }
  // The contact frequency every hooke_slider contact shares (V_max / Delta_max) [rad/s].
  double omega0() const { return spec_.v_max / spec_.overlap_max; }

 private:
  SceneSpec spec_;
  HookeSlider pair_law_, substrate_law_, spreader_law_;
  std::optional<spreader::Roller> roller_;
  std::unique_ptr<engine::Simulation<double>> sim_;
};

// The lattice heap of `spec` (positions, radii; velocities zero or jittered).
engine::ParticleSet lattice_heap(const SceneSpec &spec);

// hooke_slider bound from its schema defaults with these values, as the host binds a workflow's.
HookeSlider bind_hooke_slider(double v_max, double overlap_max, const Material &m);

// The critical step of `spec`'s scene (built with the automatic step, never run).
double critical_dt_of(const SceneSpec &spec);

}  // namespace spreadmap::extremes
