// A cylinder wall of a scene file, given to the engine as a geometry (engine::GeometryWall) with an
// ops table the host builds itself (the SDK's GeometryOps), so no plugin is needed.
//
// The cylinder has a unit axis a, a base centre c (the middle of its bottom end), a height H and a
// radius R. `inside`: particles live inside a tube open at both ends (a drum, a lifted cylinder);
// a sphere touches the lateral surface only while its centre lies inside, between the two ends
// (particles outside the tube do not feel it). Otherwise particles live outside a solid cylinder (a
// pillar), end faces and rims included. The body translates with `velocity` from time `start` to
// `stop` (at rest before and after) and turns about its own axis at `omega` [rad/s] (right-hand rule
// about a): surface velocity v + omega a x (X - c) at a surface point X. Overlap = sphere radius - distance of its centre to the surface; the normal points from
// the surface into the sphere. SI units.
#pragma once
#include <spreadmap/geometry.hpp>

#include <cmath>

namespace spreadmap::scene {

struct CylinderWall {
  double base[3];      // c at time 0 [m]
  double axis[3];      // a, unit
  double height;       // H [m]
  double radius;       // R [m]
  double velocity[3];  // [m/s]
  double start;        // the translation starts [s]
  double stop;         // and stops [s]
  double omega;        // about a [rad/s]
  bool inside;

  template <class Real> SM_HD Vec3<Real> centre_at(Real t) const {
    const Real moving = t < Real(start) ? Real(0) : t > Real(stop) ? Real(stop - start) : t - Real(start);
    return {Real(base[0]) + Real(velocity[0]) * moving, Real(base[1]) + Real(velocity[1]) * moving,
            Real(base[2]) + Real(velocity[2]) * moving};
  }

  template <class Real> SM_HD bool operator()(const Vec3<Real> &p, Real r, Real t, WallHit<Real> &hit) const {
    const Vec3<Real> a{Real(axis[0]), Real(axis[1]), Real(axis[2])};
    const Vec3<Real> c = centre_at(t);
    const Vec3<Real> q = p - c;
    const Real h = dot(q, a), top = Real(height), R = Real(radius);
    const Vec3<Real> radial = q - a * h;
    const Real d = norm(radial);
    Real dist;  // signed distance of the centre to the surface, on the particles' side
    Vec3<Real> n;
    if (inside) {  // a centre outside the tube (or beyond its ends) does not touch it
      if (!(h >= Real(0) && h <= top) || !(d > Real(0)) || !(d < R)) return false;
      dist = R - d;
      n = radial * (Real(-1) / d);
    } else {
      const Vec3<Real> out = d > Real(0) ? radial * (Real(1) / d) : Vec3<Real>{Real(0), Real(0), Real(0)};
      const Real below = -h, above = h - top, beyond = d - R;
      if (below <= Real(0) && above <= Real(0)) {  // beside the lateral surface, or inside the body
        dist = beyond;
        n = out;
        if (below > dist) {  // inside the body, nearer the bottom face than the side
          dist = below;
          n = a * Real(-1);
        }
        if (above > dist) {
          dist = above;
          n = a;
        }
        if (dist == beyond && !(d > Real(0))) return false;  // on the axis inside: no direction
      } else {
        const Real axial = below > Real(0) ? -below : above;  // signed, along a, beyond the end face
        if (beyond <= Real(0)) {
          dist = below > Real(0) ? below : above;
          n = a * (axial < Real(0) ? Real(-1) : Real(1));
        } else {  // beyond the rim
          const Vec3<Real> e = out * beyond + a * axial;
          dist = norm(e);
          n = e * (Real(1) / dist);
        }
      }
    }
    const Real overlap = r - dist;
    if (!(overlap > Real(0))) return false;
    const Vec3<Real> arm = p - n * dist - c;  // from the base centre to the contact point
    const Real moving = t > Real(start) && t < Real(stop) ? Real(1) : Real(0);
    const Vec3<Real> spin = cross(a * Real(omega), arm);
    hit.overlap = overlap;
    hit.normal = n;
    hit.velocity = {Real(velocity[0]) * moving + spin.x, Real(velocity[1]) * moving + spin.y,
                    Real(velocity[2]) * moving + spin.z};
    return true;
  }

  double max_surface_speed() const {
    return std::sqrt(velocity[0] * velocity[0] + velocity[1] * velocity[1] + velocity[2] * velocity[2]) +
           std::fabs(omega) * radius;
  }
  // Nothing for the spreading figures: a scene's cylinder is not a spreader.
  void describe(sm_spreader_description_v2 *) const {}
  void pose(double t, sm_spreader_pose_v2 *out) const {
    const Vec3<double> c = centre_at(t);
    out->reference[0] = c.x;
    out->reference[1] = c.y;
    out->reference[2] = c.z;
  }
};

// The ops table the engine calls for a CylinderWall (`self` points to one).
inline const sm_spreader_ops_v2 &cylinder_wall_ops() { return detail::GeometryOps<CylinderWall>::table; }

}  // namespace spreadmap::scene
