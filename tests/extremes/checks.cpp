#include "extremes/checks.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>

namespace spreadmap::extremes {

std::string first_non_finite(const engine::ParticleSet &s) {
  for (std::size_t i = 0; i < s.size(); ++i) {
    const double values[] = {s.x[i],  s.y[i],  s.z[i],  s.vx[i],     s.vy[i],  s.vz[i],
                             s.wx[i], s.wy[i], s.wz[i], s.radius[i], s.mass[i]};
    for (double v : values)
      if (!std::isfinite(v))
        return fmt::format("particle id {}: x = ({}, {}, {}) m, v = ({}, {}, {}) m/s, w = ({}, {}, {}) rad/s", s.id[i],
                           s.x[i], s.y[i], s.z[i], s.vx[i], s.vy[i], s.vz[i], s.wx[i], s.wy[i], s.wz[i]);
  }
  return "";
}

double deepest_substrate_overlap(const engine::ParticleSet &s) {
  double deepest = -1;
  for (std::size_t i = 0; i < s.size(); ++i) deepest = std::max(deepest, (s.radius[i] - s.z[i]) / (2 * s.radius[i]));
  return deepest;
}

RollerOverlap roller_overlap(const spreader::Roller &roller, const engine::ParticleSet &s, double t) {
  RollerOverlap out{-1, 0};
  for (std::size_t i = 0; i < s.size(); ++i) {
    WallHit<double> hit{0, {0, 0, 1}, {0, 0, 0}};
    if (roller(Vec3<double>{s.x[i], s.y[i], s.z[i]}, s.radius[i], t, hit))
      out.deepest = std::max(out.deepest, hit.overlap / (2 * s.radius[i]));
    // The solid itself: a zero-radius probe at the centre touches it only from inside.
    WallHit<double> centre{0, {0, 0, 1}, {0, 0, 0}};
    if (roller(Vec3<double>{s.x[i], s.y[i], s.z[i]}, 0.0, t, centre)) ++out.centre_inside;
  }
  return out;
}

Energy mechanical_energy(const Scene &scene) {
  const auto &sim = scene.sim();
  const engine::ParticleSet s = sim.state();
  const SceneSpec &spec = scene.spec();
  const double w2 = scene.omega0() * scene.omega0(), g = spec.gravity;
  Energy e;
  auto spring = [&](double m_eq, double overlap) {
    if (overlap > 0) e.elastic += 0.5 * m_eq * w2 * overlap * overlap;
  };
  for (std::size_t i = 0; i < s.size(); ++i) {
    const double m = s.mass[i], r = s.radius[i];
    e.kinetic += 0.5 * m * (s.vx[i] * s.vx[i] + s.vy[i] * s.vy[i] + s.vz[i] * s.vz[i]);
    e.rotational += 0.5 * 0.4 * m * r * r * (s.wx[i] * s.wx[i] + s.wy[i] * s.wy[i] + s.wz[i] * s.wz[i]);
    e.gravity += m * g * (s.z[i] - r);
    spring(m, r - s.z[i]);
    if (spec.end_walls) {
      spring(m, r - s.x[i]);
      spring(m, s.x[i] + r - spec.length);
    }
    if (scene.has_roller()) {
      WallHit<double> hit{0, {0, 0, 1}, {0, 0, 0}};
      if (scene.roller()(Vec3<double>{s.x[i], s.y[i], s.z[i]}, r, sim.time(), hit)) spring(m, hit.overlap);
    }
    for (std::size_t j = i + 1; j < s.size(); ++j) {
      double dy = s.y[i] - s.y[j];
      dy -= spec.width * std::round(dy / spec.width);  // periodic y
      const double dx = s.x[i] - s.x[j], dz = s.z[i] - s.z[j];
      const double reach = r + s.radius[j];
      const double d2 = dx * dx + dy * dy + dz * dz;
      if (d2 < reach * reach) spring(m * s.mass[j] / (m + s.mass[j]), reach - std::sqrt(d2));
    }
  }
  return e;
}

double top_speed(const engine::ParticleSet &s) {
  double v2 = 0;
  for (std::size_t i = 0; i < s.size(); ++i)
    v2 = std::max(v2, s.vx[i] * s.vx[i] + s.vy[i] * s.vy[i] + s.vz[i] * s.vz[i]);
  return std::sqrt(v2);
}

}  // namespace spreadmap::extremes
