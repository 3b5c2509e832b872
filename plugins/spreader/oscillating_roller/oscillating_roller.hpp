// spreader/oscillating_roller: a roller whose rotation oscillates about a mean, as studied for fine,
// cohesive powders (a counter-rotating roller with a superposed oscillation breaks up agglomerates
// and bridges in front of it).
//
// While it travels, its angular velocity about +y is
//     w(t) = omega + A 2 pi f sin(2 pi f t),
// so its angle is theta(t) = omega t + A (1 - cos(2 pi f t)): an oscillation of amplitude A [rad] and
// frequency f [1/s] about the steady rotation omega. Before the start and after the travel it rests,
// as every spreader does. The body, its travel and its sign conventions are those of a roller
// (spreadmap/spreader/cylinder.hpp): omega > 0 rolls forward, omega < 0 counter-rotates.
#pragma once
#include <spreadmap/geometry.hpp>
#include <spreadmap/params.hpp>
#include <spreadmap/spreader/cylinder.hpp>

#include <cmath>

namespace spreadmap::spreader {

struct OscillatingRoller {
  static constexpr sm_param_v1 params[] = {
      param_diameter("D: roller diameter (radius R = D/2)"),
      param_length("length along y of the roller, centred on y_centre; flat end faces"),
      param_y_centre(),
      param_gap("gap between the roller's lowest point and the substrate z = 0: the axis is at z = gap + R"),
      param_speed(),
      number("omega", "rad/s", -1e4, 1e4, 0.0,
             "omega: mean angular velocity about +y; > 0 rolls forward, < 0 counter-rotates"),
      number("amplitude", "rad", 0.0, 100.0, 0.1,
             "A: angular amplitude of the oscillation; the angle is omega t + A (1 - cos(2 pi f t))"),
      number("frequency", "1/s", 0.0, 1e5, 50.0, "f: frequency of the oscillation (0: none)"),
      param_start("x of the roller axis at t = 0 (time counted from the start of spreading)"),
      param_travel(),
      param_end(),
  };

  Cylinder body;
  double omega;              // [rad/s]
  double amplitude;          // A [rad]
  double angular_frequency;  // 2 pi f [rad/s]

  static OscillatingRoller bind(const Values &v) {
    constexpr double two_pi = 6.283185307179586;
    return {Cylinder::bind(v), v["omega"], v["amplitude"], two_pi * v["frequency"]};
  }

  // w(t) while travelling, 0 at rest.
  template <class Real> SM_HD Real angular_velocity(Real t) const {
    if (!body.travel.moving(t)) return Real(0);
    const Real k = static_cast<Real>(angular_frequency);
    return static_cast<Real>(omega) + static_cast<Real>(amplitude) * k * std::sin(k * t);
  }

  template <class Real> SM_HD bool operator()(const Vec3<Real> &p, Real r, Real t, WallHit<Real> &hit) const {
    return body.touch(p, r, t, angular_velocity(t), hit);
  }

  double max_surface_speed() const {
    return body.travel.speed + (std::abs(omega) + amplitude * angular_frequency) * body.radius;
  }
  void describe(sm_spreader_description_v2 *out) const { body.describe(out); }
  void pose(double t, sm_spreader_pose_v2 *out) const {
    const double s = body.travel.elapsed(t);  // the rotation stops with the travel
    body.pose(t, omega * s + amplitude * (1 - std::cos(angular_frequency * s)), angular_velocity(t), out);
  }
};

}  // namespace spreadmap::spreader
