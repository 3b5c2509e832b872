// spreader/roller: a solid cylinder, axis along y, translating along +x at U and turning at a
// constant omega about +y while it travels (the body and its conventions: spreadmap/spreader/
// cylinder.hpp). omega > 0 turns the roller like a wheel rolling forward (omega = U/R: its bottom
// surface is at rest), omega < 0 counter-rotates (its bottom surface moves forward at U + |omega| R).
// Both motions stop when the travel ends.
#pragma once
#include <spreadmap/geometry.hpp>
#include <spreadmap/params.hpp>
#include <spreadmap/spreader/cylinder.hpp>

namespace spreadmap::spreader {

struct Roller {
  static constexpr sm_param_v1 params[] = {
      param_diameter("D: roller diameter (radius R = D/2)"),
      param_length("length along y of the roller, centred on y_centre; flat end faces"),
      param_y_centre(),
      param_gap("gap between the roller's lowest point and the substrate z = 0: the axis is at z = gap + R"),
      param_speed(),
      number("omega", "rad/s", -1e4, 1e4, 0.0,
             "omega: angular velocity about +y; > 0 rolls forward (omega = U/R: bottom at rest), "
             "< 0 counter-rotates"),
      param_start("x of the roller axis at t = 0 (time counted from the start of spreading)"),
      param_travel(),
      param_end(),
  };

  Cylinder body;
  double omega;  // [rad/s]

  static Roller bind(const Values &v) { return {Cylinder::bind(v), v["omega"]}; }

  template <class Real> SM_HD bool operator()(const Vec3<Real> &p, Real r, Real t, WallHit<Real> &hit) const {
    return body.touch(p, r, t, body.travel.moving(t) ? static_cast<Real>(omega) : Real(0), hit);
  }

  double max_surface_speed() const { return body.travel.speed + (omega < 0 ? -omega : omega) * body.radius; }
  void describe(sm_spreader_description_v2 *out) const { body.describe(out); }
  void pose(double t, sm_spreader_pose_v2 *out) const {
    body.pose(t, omega * body.travel.elapsed(t), body.travel.moving(t) ? omega : 0.0, out);
  }
};

}  // namespace spreadmap::spreader
