// An out-of-tree spreader built only from the installed SDK: a flat scraper, a rectangle of
// `thickness` x `height` in the x-z plane whose lowest edge slides at `gap` over the substrate, moved
// by the SDK's straight travel (start, U, travel or end) and extruded along y with flat ends. It
// describes itself (outline, travel, gap), so the host runs and draws it without knowing its name.
#include <spreadmap/geometry.hpp>
#include <spreadmap/params.hpp>
#include <spreadmap/spreader/extruded_profile.hpp>
#include <spreadmap/spreader/outline.hpp>
#include <spreadmap/spreader/travel.hpp>

namespace sp = spreadmap::spreader;

struct Scraper {
  static constexpr sm_param_v1 params[] = {
      spreadmap::number("thickness", "m", 1e-5, 0.1, 1e-3, "t: scraper thickness along x"),
      spreadmap::number("height", "m", 1e-5, 1.0, 10e-3, "scraper height above its lowest edge"),
      sp::param_length("length along y, centred on y_centre; flat end faces"),
      sp::param_y_centre(),
      sp::param_gap("gap between the scraper's lowest edge and the substrate z = 0"),
      sp::param_speed(),
      sp::param_start("x of the scraper's mid-plane at t = 0"),
      sp::param_travel(),
      sp::param_end(),
  };

  sp::Travel travel;
  double half_thickness, half_height, length, y_centre, gap;

  static Scraper bind(const spreadmap::Values &v) {
    return {sp::Travel::bind(v), 0.5 * v["thickness"], 0.5 * v["height"], v["length"], v["y_centre"], v["gap"]};
  }

  template <class Real>
  SM_HD bool operator()(const spreadmap::Vec3<Real> &p, Real r, Real t, spreadmap::WallHit<Real> &hit) const {
    const Real u = p.x - travel.x(t), w = p.z - Real(gap + half_height);
    const auto d = sp::rounded_rectangle_distance(u, w, Real(half_thickness), Real(half_height), Real(0));
    spreadmap::Vec3<Real> n{};
    const Real dist = sp::extruded_distance(d, p.y - Real(y_centre), Real(0.5 * length), n);
    if (!(r - dist > Real(0))) return false;
    hit.overlap = r - dist;
    hit.normal = n;
    hit.velocity = {travel.velocity(t), Real(0), Real(0)};
    return true;
  }

  double max_surface_speed() const { return travel.speed; }
  void describe(spreadmap::sm_spreader_description_v2 *out) const {
    sp::add_vertex(out, -half_thickness, 0);
    sp::add_vertex(out, half_thickness, 0);
    sp::add_vertex(out, half_thickness, 2 * half_height);
    sp::add_vertex(out, -half_thickness, 2 * half_height);
    out->y_centre = y_centre;
    out->length = length;
    travel.describe(out);
    out->gap = gap;
  }
  void pose(double t, spreadmap::sm_spreader_pose_v2 *out) const {
    out->reference[0] = travel.x(t);
    out->reference[1] = y_centre;
    out->reference[2] = gap;
    out->velocity[0] = travel.velocity(t);
    out->x_min = out->reference[0] - half_thickness;
    out->x_max = out->reference[0] + half_thickness;
  }
};

SPREADMAP_SPREADER_PLUGIN(Scraper, "scraper", "0.1.0", "a flat scraper blade built out of tree")
