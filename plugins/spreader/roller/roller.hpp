// spreader/roller: a solid cylinder, axis along y, translating along +x at U and turning at omega.
//
// Conventions (paper-notes.md): x is the spreading direction, z up, the substrate top is z = 0.
// omega is the angular velocity about +y (right-hand rule): omega > 0 turns the roller like a wheel
// rolling forward (omega = U/R: its bottom surface is at rest), omega < 0 counter-rotates (its
// bottom surface moves forward at U + |omega| R). Surface velocity at a surface point p:
// v = U e_x + (omega e_y) x (p - c), c the axis point. Both motions stop when the travel ends.
//
// Geometry: axis at (x_c(t), z = gap + R), x_c(t) = start + U min(max(t, 0), travel / U); the
// cylinder spans |y - y_centre| <= length / 2 and has flat end faces (a roller longer than a
// periodic strip simply spans it). Overlap with a sphere = radius - signed distance of its centre
// to the solid; normal from the roller surface into the sphere. SI units throughout.
#pragma once
#include <spreadmap/geometry.hpp>
#include <spreadmap/params.hpp>

#include <cstdio>

#include "../common/extruded_profile.hpp"
#include "../common/travel.hpp"

namespace spreadmap::spreader {

struct Roller {
  static constexpr sm_param_v1 params[] = {
      number("diameter", "m", 1e-4, 1.0, 10e-3, "D: roller diameter (radius R = D/2)"),
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

  Travel travel;
  double radius;     // R [m]
  double length;     // [m]
  double y_centre;   // [m]
  double axis_z;     // gap + R [m]
  double omega;      // [rad/s]

  static Roller bind(const Values &v) {
    const double radius = 0.5 * v["diameter"];
    return {Travel::bind(v), radius, v["length"], v["y_centre"], v["gap"] + radius, v["omega"]};
  }

  template <class Real>
  SM_HD bool operator()(const Vec3<Real> &p, Real r, Real t, WallHit<Real> &hit) const {
    const Real cx = travel.x(t), cz = static_cast<Real>(axis_z), R = static_cast<Real>(radius);
    const Real dx = p.x - cx, dz = p.z - cz;
    const Real d = std::sqrt(dx * dx + dz * dz);
    // A centre on the axis has no defined direction: push it down, towards the substrate side.
    const ProfileDistance<Real> disc = d > Real(0) ? ProfileDistance<Real>{d - R, dx / d, dz / d}
                                                   : ProfileDistance<Real>{-R, Real(0), Real(-1)};
    Vec3<Real> n{};
    const Real dist = extruded_distance(disc, p.y - static_cast<Real>(y_centre), static_cast<Real>(0.5 * length), n);
    const Real overlap = r - dist;
    if (!(overlap > Real(0))) return false;
    // Contact point: the surface point nearest the centre; its rigid-body velocity.
    const Vec3<Real> arm{p.x - dist * n.x - cx, Real(0), p.z - dist * n.z - cz};
    const Real w = travel.moving(t) ? static_cast<Real>(omega) : Real(0);
    hit.overlap = overlap;
    hit.normal = n;
    hit.velocity = {travel.velocity(t) + w * arm.z, Real(0), -w * arm.x};  // U e_x + w e_y x arm
    return true;
  }

  double duration() const { return travel.duration; }
  double max_surface_speed() const { return travel.speed + (omega < 0 ? -omega : omega) * radius; }

  void pose(double t, sm_pose_v1 *out) const {
    *out = sm_pose_v1{};
    std::snprintf(out->shape, sizeof out->shape, "%s", "cylinder");
    out->centre[0] = travel.x(t);
    out->centre[1] = y_centre;
    out->centre[2] = axis_z;
    out->radius = radius;
    out->length = length;
    out->angle = omega * travel.elapsed(t);
    out->velocity[0] = travel.velocity(t);
    out->omega = travel.moving(t) ? omega : 0.0;
  }
};

}  // namespace spreadmap::spreader
