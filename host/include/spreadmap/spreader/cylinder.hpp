// A solid cylinder with its axis along y that moves on a straight travel (travel.hpp) and turns
// about its axis: the body of rotating spreaders, whose plugins add how fast it turns.
//
// Conventions (x spreading direction, z up, substrate top z = 0): the axis is at
// (x_c(t), z = gap + R); the cylinder spans |y - y_centre| <= length / 2 with flat end faces (one
// longer than a periodic strip simply spans it). An angular velocity w about +y (right-hand rule)
// > 0 turns it like a wheel rolling forward (w = U/R: its bottom surface is at rest). Surface
// velocity at a surface point p: v = U e_x + (w e_y) x (p - c), c the axis point. Overlap with a
// sphere = radius - signed distance of its centre to the solid; normal from the surface into the
// sphere. SI units throughout.
#pragma once
#include <spreadmap/geometry.hpp>
#include <spreadmap/params.hpp>
#include <spreadmap/spreader/extruded_profile.hpp>
#include <spreadmap/spreader/outline.hpp>
#include <spreadmap/spreader/travel.hpp>

namespace spreadmap::spreader {

constexpr sm_param_v1 param_diameter(const char *doc) { return number("diameter", "m", 1e-4, 1.0, 10e-3, doc); }

struct Cylinder {
  Travel travel;
  double radius;    // R [m]
  double length;    // [m]
  double y_centre;  // [m]
  double axis_z;    // gap + R [m]
  double gap;       // [m]

  // Host only. Reads diameter, length, y_centre, gap and the travel's keys.
  static Cylinder bind(const Values &v) {
    const double radius = 0.5 * v["diameter"];
    return {Travel::bind(v), radius, v["length"], v["y_centre"], v["gap"] + radius, v["gap"]};
  }

  // The contact of a sphere (centre p, radius r) at time t with the cylinder turning at w [rad/s].
  template <class Real> SM_HD bool touch(const Vec3<Real> &p, Real r, Real t, Real w, WallHit<Real> &hit) const {
    const Real cx = travel.x(t), cz = static_cast<Real>(axis_z), R = static_cast<Real>(radius);
    const Real dx = p.x - cx, dz = p.z - cz;
    const Real d = std::sqrt(dx * dx + dz * dz);
    // A centre on the axis has no defined direction: push it down, towards the substrate side.
    const ProfileDistance<Real> disc =
        d > Real(0) ? ProfileDistance<Real>{d - R, dx / d, dz / d} : ProfileDistance<Real>{-R, Real(0), Real(-1)};
    Vec3<Real> n{};
    const Real dist = extruded_distance(disc, p.y - static_cast<Real>(y_centre), static_cast<Real>(0.5 * length), n);
    const Real overlap = r - dist;
    if (!(overlap > Real(0))) return false;
    // Contact point: the surface point nearest the centre; its rigid-body velocity.
    const Vec3<Real> arm{p.x - dist * n.x - cx, Real(0), p.z - dist * n.z - cz};
    hit.overlap = overlap;
    hit.normal = n;
    hit.velocity = {travel.velocity(t) + w * arm.z, Real(0), -w * arm.x};  // U e_x + w e_y x arm
    return true;
  }

  // Host only. The disc about the axis (72 sides drawn), the travel and the gap.
  void describe(sm_spreader_description_v2 *out) const {
    add_circle(out, radius, 72);
    out->y_centre = y_centre;
    out->length = length;
    out->turns = 1;
    travel.describe(out);
    out->gap = gap;
  }

  // Host only. The pose at time t, turned by `angle` and turning at `omega` then.
  void pose(double t, double angle, double omega, sm_spreader_pose_v2 *out) const {
    out->reference[0] = travel.x(t);
    out->reference[1] = y_centre;
    out->reference[2] = axis_z;
    out->angle = angle;
    out->velocity[0] = travel.velocity(t);
    out->omega = omega;
    out->x_min = out->reference[0] - radius;
    out->x_max = out->reference[0] + radius;
  }
};

}  // namespace spreadmap::spreader
