#include "extremes/scene.hpp"

#include <spreadmap/geometry.hpp>

#include <cmath>
#include <random>

#include "unit/spreader_values.hpp"

namespace spreadmap::extremes {

using engine::ParticleSet;

HookeSlider bind_hooke_slider(double v_max, double overlap_max, const Material &m) {
  return test::bind_with<HookeSlider>(
      {{"v_max", v_max}, {"overlap_max", overlap_max}, {"restitution", m.restitution}, {"friction", m.friction}});
}

ParticleSet lattice_heap(const SceneSpec &spec) {
  // Spheres 4 % apart: touching neighbours would start loaded; farther apart the heap falls further.
  const double d = spec.diameter, r = 0.5 * d, pitch = 1.04 * d;
  const std::size_t per_row = std::max<std::size_t>(1, std::size_t(spec.width / pitch));
  const double pitch_y = spec.width / double(per_row);
  const std::size_t layers = std::max<std::size_t>(1, spec.layers);
  const std::size_t per_layer = (spec.count + layers - 1) / layers;
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  ParticleSet s;
  for (std::size_t k = 0; k < spec.count; ++k) {
    const std::size_t layer = k / per_layer, in_layer = k % per_layer;
    const std::size_t column = in_layer / per_row, row = in_layer % per_row;
    s.x.push_back(spec.heap_from + r + double(column) * pitch + 0.01 * d * u(rng));
    s.y.push_back((double(row) + 0.5) * pitch_y + 0.01 * d * u(rng));
    s.z.push_back(r + 1e-6 + spec.drop + double(layer) * pitch);
    s.radius.push_back(r);
    s.vx.push_back(spec.jitter_speed * u(rng));
    s.vy.push_back(spec.jitter_speed * u(rng));
    s.vz.push_back(spec.jitter_speed * u(rng) - spec.fall_speed);
  }
  s.wx.assign(s.size(), 0);
  s.wy.assign(s.size(), 0);
  s.wz.assign(s.size(), 0);
  return s;
}

Scene::Scene(const SceneSpec &spec)
    : spec_(spec),
      pair_law_(bind_hooke_slider(spec.v_max, spec.overlap_max, spec.particles)),
      substrate_law_(bind_hooke_slider(spec.v_max, spec.overlap_max, spec.substrate)),
      spreader_law_(bind_hooke_slider(spec.v_max, spec.overlap_max, spec.spreader_surface)) {
  using Ops = detail::ContactOps<HookeSlider>;
  auto law = [](const HookeSlider &l) { return engine::ContactLaw{&Ops::table, &l}; };
  engine::Settings settings;
  settings.dt = spec.dt;
  settings.dt_safety = spec.dt_safety;
  settings.allow_unstable_dt = spec.allow_unstable_dt;
  settings.gravity = {0, 0, -spec.gravity};
  settings.log = [](const std::string &) {};
  const engine::Domain domain{{0, 0, 0}, {spec.length, spec.width, spec.height}, {false, true, false}};
  sim_ = std::make_unique<engine::Simulation<double>>(domain, law(pair_law_), settings);
  sim_->add_plane_wall({{0, 0, 0}, {0, 0, 1}, {0, 0, 0}, law(substrate_law_), true, "substrate"});
  if (spec.end_walls) {
    sim_->add_plane_wall({{0, 0, 0}, {1, 0, 0}, {0, 0, 0}, law(substrate_law_), true, "back wall"});
    sim_->add_plane_wall({{spec.length, 0, 0}, {-1, 0, 0}, {0, 0, 0}, law(substrate_law_), true, "front wall"});
  }
  if (spec.U > 0) {
    roller_ = test::bind_with<spreader::Roller>({{"diameter", spec.roller_diameter},
                                                 {"gap", spec.gap},
                                                 {"U", spec.U},
                                                 {"omega", spec.omega},
                                                 {"start", spec.start},
                                                 {"travel", spec.travel}});
    sim_->add_geometry(
        {&detail::GeometryOps<spreader::Roller>::table, &*roller_, law(spreader_law_), "spreader/roller"});
  }
  if (spec.count > 0) sim_->add_particles(lattice_heap(spec), spec.density);
}

double critical_dt_of(const SceneSpec &spec) {
  SceneSpec probe = spec;
  probe.dt = 0;
  return Scene(probe).sim().critical_dt();
}

}  // namespace spreadmap::extremes
