// Spreader geometries: analytic moving surfaces. The plugin's functor answers, for one sphere at
// time t, whether it touches the surface and with what overlap, normal and surface velocity; the
// SDK loop fills the dense per-particle WallContacts record that contact laws consume. Laws and
// geometries therefore combine freely, with no template cross product.
//
// A geometry provides:
//   static constexpr sm_param_v1 params[];  static Geometry bind(const sm::Values &);
//   template <class Real> SM_HD bool operator()(const Vec3<Real>& centre, Real radius, Real t, WallHit<Real>&) const;
//   double duration() const;              seconds from the start to the end of its travel
//   double max_surface_speed() const;     largest speed of any surface point [m/s]
//   void pose(double t, sm_pose_v1 *) const;  where it is at time t (figures, checks)
#pragma once
#include <spreadmap/batch.hpp>
#include <spreadmap/hd.hpp>
#include <spreadmap/plugin.hpp>
#include <spreadmap/team.hpp>

#include <type_traits>

namespace spreadmap {

template <class Real> struct WallHit {
  Real overlap;          // > 0 when touching [m]
  Vec3<Real> normal;     // unit, from the surface into the sphere
  Vec3<Real> velocity;   // surface velocity at the contact point [m/s]
};

extern "C" {
// Where a spreader is, for figures and checks. shape: "cylinder" (axis along y) or "blade".
typedef struct sm_pose_v1 {
  char shape[16];
  double centre[3];   // roller axis point, or the blade's lowest edge point [m]
  double radius;      // roller radius, or blade edge radius [m]
  double length;      // extent along y [m]
  double thickness;   // blade thickness along x [m] (0 for a roller)
  double height;      // blade height above its edge [m] (0 for a roller)
  double angle;       // roller rotation angle about +y since the start [rad]
  double velocity[3]; // translation velocity [m/s]
  double omega;       // angular velocity about +y [rad/s]
} sm_pose_v1;

typedef struct sm_geometry_ops_v1 {
  void (*contacts_f64)(const void *self, const Particles<double> *p, WallContacts<double> *out);
  void (*contacts_f32)(const void *self, const Particles<float> *p, WallContacts<float> *out);
  double (*duration)(const void *self);
  double (*max_surface_speed)(const void *self);
  void (*pose)(const void *self, double t, sm_pose_v1 *out);
} sm_geometry_ops_v1;
}

// Particle i's dense wall-contact record for this geometry at time p.t. The body of both backends'
// geometry loops.
template <class Geometry, class Real>
SM_HD void geometry_contact_of(const Geometry &g, const Particles<Real> &p, const WallContacts<Real> &w, std::uint32_t i) {
  WallHit<Real> hit{0, {0, 0, 1}, {0, 0, 0}};
  if (g(Vec3<Real>{p.x[i], p.y[i], p.z[i]}, p.r[i], p.t, hit) && hit.overlap > 0) {
    w.overlap[i] = hit.overlap;
    w.nx[i] = hit.normal.x; w.ny[i] = hit.normal.y; w.nz[i] = hit.normal.z;
    w.vx[i] = hit.velocity.x; w.vy[i] = hit.velocity.y; w.vz[i] = hit.velocity.z;
  } else {
    w.overlap[i] = 0;
  }
}

template <class Geometry, class Real>
void geometry_loop(const Geometry &g, const Particles<Real> &p, WallContacts<Real> &w) {
  parallel_for(p.team, p.n, [&](long long i) { geometry_contact_of(g, p, w, static_cast<std::uint32_t>(i)); });
}

namespace detail {
template <class G> struct GeometryOps {
  static const G &geo(const void *s) { return *static_cast<const G *>(s); }
  static void c64(const void *s, const Particles<double> *p, WallContacts<double> *w) { geometry_loop(geo(s), *p, *w); }
  static void c32(const void *s, const Particles<float> *p, WallContacts<float> *w) { geometry_loop(geo(s), *p, *w); }
  static double duration(const void *s) { return geo(s).duration(); }
  static double speed(const void *s) { return geo(s).max_surface_speed(); }
  static void pose(const void *s, double t, sm_pose_v1 *out) { geo(s).pose(t, out); }
  static constexpr sm_geometry_ops_v1 table = {&c64, &c32, &duration, &speed, &pose};
};
}  // namespace detail
}  // namespace spreadmap

#define SPREADMAP_SPREADER_PLUGIN(GEOMETRY, NAME, VERSION, SUMMARY)                                  \
  static_assert(std::is_trivially_copyable_v<GEOMETRY>, "a spreader geometry must be trivially copyable"); \
  SPREADMAP_PLUGIN("spreader", GEOMETRY, NAME, VERSION, SUMMARY, &::spreadmap::detail::GeometryOps<GEOMETRY>::table)
