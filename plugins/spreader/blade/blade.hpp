// spreader/blade: a vertical slab (doctor blade) translating along +x at U, no rotation.
//
// Profile in the x–z plane: the rectangle x in [x_c - thickness/2, x_c + thickness/2],
// z in [gap, gap + height], its two lower corners rounded with radius edge_radius (0 = sharp
// corners; the distance to a sharp corner is the distance to the corner point). Top corners are
// sharp. Extruded along y over |y - y_centre| <= length/2 with flat end faces. x_c(t) follows the
// straight travel of travel.hpp. Overlap with a sphere = radius - signed distance of its centre
// to the solid; normal from the blade into the sphere; surface velocity U e_x while moving.
#pragma once
#include <spreadmap/geometry.hpp>
#include <spreadmap/params.hpp>

#include <cstdio>
#include <string>

#include "../common/extruded_profile.hpp"
#include "../common/travel.hpp"

namespace spreadmap::spreader {

// Signed distance and outward normal of a rectangle with rounded lower corners, in coordinates
// relative to its centre (u along x, w along z). Half sizes hx, hz; lower corner radius rho
// (<= min(hx, hz)).
template <class Real>
SM_HD ProfileDistance<Real> rounded_rectangle_distance(Real u, Real w, Real hx, Real hz, Real rho) {
  const Real su = u < Real(0) ? Real(-1) : Real(1), sw = w < Real(0) ? Real(-1) : Real(1);
  const Real corner = w < Real(0) ? rho : Real(0);
  // Fold into the first quadrant; (qx, qz) is the offset from the rectangle shrunk by `corner`.
  const Real qx = su * u - (hx - corner), qz = sw * w - (hz - corner);
  if (qx > Real(0) && qz > Real(0)) {  // facing a corner: nearest point on its arc
    const Real q = std::sqrt(qx * qx + qz * qz);
    return {q - corner, su * qx / q, sw * qz / q};
  }
  if (qx >= qz) return {qx - corner, su, Real(0)};  // nearest point on a vertical face
  return {qz - corner, Real(0), sw};                // nearest point on the top or bottom face
}

struct Blade {
  static constexpr sm_param_v1 params[] = {
      number("thickness", "m", 1e-6, 0.1, 1e-3, "t: blade thickness along x"),
      number("edge_radius", "m", 0.0, 0.05, 0.0,
             "radius of the two rounded lower edges, <= thickness/2 and <= height/2; 0 = sharp edges"),
      number("height", "m", 1e-6, 1.0, 10e-3, "blade height above its lowest point (top at gap + height)"),
      param_length("length along y of the blade, centred on y_centre; flat end faces"),
      param_y_centre(),
      param_gap("gap between the blade's lowest point and the substrate z = 0"),
      param_speed(),
      param_start("x of the blade mid-plane at t = 0 (time counted from the start of spreading)"),
      param_travel(),
      param_end(),
  };

  Travel travel;
  double half_thickness;  // [m]
  double half_height;     // [m]
  double edge_radius;     // [m]
  double length;          // [m]
  double y_centre;        // [m]
  double gap;             // [m]

  static Blade bind(const Values &v) {
    const double thickness = v["thickness"], height = v["height"], rho = v["edge_radius"];
    if (rho > 0.5 * thickness || rho > 0.5 * height)
      throw ParamError("edge_radius = " + text_of(rho) + " m exceeds half the thickness (" +
                       text_of(0.5 * thickness) + " m) or half the height (" + text_of(0.5 * height) +
                       " m): lower it or make the blade thicker");
    return {Travel::bind(v), 0.5 * thickness, 0.5 * height, rho, v["length"], v["y_centre"], v["gap"]};
  }

  template <class Real>
  SM_HD bool operator()(const Vec3<Real> &p, Real r, Real t, WallHit<Real> &hit) const {
    const Real u = p.x - travel.x(t), w = p.z - static_cast<Real>(gap + half_height);
    const ProfileDistance<Real> profile =
        rounded_rectangle_distance(u, w, static_cast<Real>(half_thickness), static_cast<Real>(half_height),
                                   static_cast<Real>(edge_radius));
    Vec3<Real> n{};
    const Real dist = extruded_distance(profile, p.y - static_cast<Real>(y_centre), static_cast<Real>(0.5 * length), n);
    const Real overlap = r - dist;
    if (!(overlap > Real(0))) return false;
    hit.overlap = overlap;
    hit.normal = n;
    hit.velocity = {travel.velocity(t), Real(0), Real(0)};
    return true;
  }

  double duration() const { return travel.duration; }
  double max_surface_speed() const { return travel.speed; }

  void pose(double t, sm_pose_v1 *out) const {
    *out = sm_pose_v1{};
    std::snprintf(out->shape, sizeof out->shape, "%s", "blade");
    out->centre[0] = travel.x(t);
    out->centre[1] = y_centre;
    out->centre[2] = gap;
    out->radius = edge_radius;
    out->length = length;
    out->thickness = 2 * half_thickness;
    out->height = 2 * half_height;
    out->velocity[0] = travel.velocity(t);
  }
};

}  // namespace spreadmap::spreader
