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

#include <spreadmap/spreader/extruded_profile.hpp>
#include <spreadmap/spreader/outline.hpp>
#include <spreadmap/spreader/travel.hpp>

#include <string>

namespace spreadmap::spreader {

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
      throw ParamError("edge_radius = " + text_of(rho) + " m exceeds half the thickness (" + text_of(0.5 * thickness) +
                       " m) or half the height (" + text_of(0.5 * height) + " m): lower it or make the blade thicker");
    return {Travel::bind(v), 0.5 * thickness, 0.5 * height, rho, v["length"], v["y_centre"], v["gap"]};
  }

  template <class Real> SM_HD bool operator()(const Vec3<Real> &p, Real r, Real t, WallHit<Real> &hit) const {
    const Real u = p.x - travel.x(t), w = p.z - static_cast<Real>(gap + half_height);
    const ProfileDistance<Real> profile = rounded_rectangle_distance(
        u, w, static_cast<Real>(half_thickness), static_cast<Real>(half_height), static_cast<Real>(edge_radius));
    Vec3<Real> n{};
    const Real dist = extruded_distance(profile, p.y - static_cast<Real>(y_centre), static_cast<Real>(0.5 * length), n);
    const Real overlap = r - dist;
    if (!(overlap > Real(0))) return false;
    hit.overlap = overlap;
    hit.normal = n;
    hit.velocity = {travel.velocity(t), Real(0), Real(0)};
    return true;
  }

  double max_surface_speed() const { return travel.speed; }

  // The rounded rectangle about the reference point, the middle of its lowest edge (z = gap).
  void describe(sm_spreader_description_v2 *out) const {
    constexpr double quarter = 1.5707963267948966;
    const double hx = half_thickness, top = 2 * half_height, rho = edge_radius;
    add_arc(out, -hx + rho, rho, rho, 2 * quarter, 3 * quarter, 8);  // lower back edge
    add_arc(out, hx - rho, rho, rho, 3 * quarter, 4 * quarter, 8);   // lower front edge
    add_vertex(out, hx, top);
    add_vertex(out, -hx, top);
    out->y_centre = y_centre;
    out->length = length;
    out->turns = 0;
    travel.describe(out);
    out->gap = gap;
  }

  void pose(double t, sm_spreader_pose_v2 *out) const {
    out->reference[0] = travel.x(t);
    out->reference[1] = y_centre;
    out->reference[2] = gap;
    out->velocity[0] = travel.velocity(t);
    out->x_min = out->reference[0] - half_thickness;
    out->x_max = out->reference[0] + half_thickness;
  }
};

}  // namespace spreadmap::spreader
