// Spreader geometries: analytic moving rigid bodies. The plugin's functor answers, for one sphere at
// time t, whether it touches the surface and with what overlap, normal and surface velocity; the
// SDK loop fills the dense per-particle WallContacts record that contact laws consume. Laws and
// geometries therefore combine freely, with no template cross product.
//
// A spreader also describes itself, so that the host needs to know none by name: its cross-section
// (for figures), its travel and speed (for the run's duration and the layer's V_s), its pose at any
// time (for figures and the sleeping region), and whether a sphere touches it (for the heap set-up,
// which keeps a clearance from the spreader at rest). Time t counts from the start of spreading; a
// spreader rests, with no surface velocity, for t < 0 (the host settles the heap there).
//
// A geometry provides:
//   static constexpr sm_param_v1 params[];  static Geometry bind(const sm::Values &);
//   template <class Real> SM_HD bool operator()(const Vec3<Real>& centre, Real radius, Real t, WallHit<Real>&) const;
//   double max_surface_speed() const;                  largest speed of any surface point [m/s]
//   void describe(sm_spreader_description_v2 *) const; outline, travel (see below)
//   void pose(double t, sm_spreader_pose_v2 *) const;  where it is at time t
#pragma once
#include <spreadmap/batch.hpp>
#include <spreadmap/hd.hpp>
#include <spreadmap/plugin.hpp>

#include <type_traits>

namespace spreadmap {

template <class Real> struct WallHit {
  Real overlap;         // > 0 when touching [m]
  Vec3<Real> normal;    // unit, from the surface into the sphere
  Vec3<Real> velocity;  // surface velocity at the contact point [m/s]
};

extern "C" {
// Most vertices of a spreader's cross-section.
#define SM_OUTLINE_MAX 192

// What a spreader is, independent of time. Its body is the polygon (x[k], z[k]), counter-clockwise,
// in the body frame (relative to the reference point, unrotated), extruded along y over
// |y - y_centre| <= length / 2. The figures draw it; `turns` asks them to mark its rotation.
typedef struct sm_spreader_description_v2 {
  uint32_t vertices;
  double x[SM_OUTLINE_MAX], z[SM_OUTLINE_MAX];  // [m]
  double y_centre, length;                      // [m]
  int turns;                                    // 1: it rotates about the reference point
  double start, end;                            // x of the reference point before (t <= 0) and after its travel [m]
  double speed;     // U: translation speed while spreading [m/s] (the layer's V_s = mean height x U)
  double duration;  // seconds from t = 0 to the end of its travel
  double gap;       // height of its lowest point above the substrate z = 0 [m]
} sm_spreader_description_v2;

// Where a spreader is at time t: the reference point, the rotation of the body about +y through it
// (right-hand rule: > 0 turns +z towards +x), their rates, and the body's extent along x.
typedef struct sm_spreader_pose_v2 {
  double reference[3];  // [m]
  double angle;         // since the start [rad]
  double velocity[3];   // of the reference point [m/s]
  double omega;         // about +y [rad/s]
  double x_min, x_max;  // [m]
} sm_spreader_pose_v2;

typedef struct sm_spreader_ops_v2 {
  void (*contacts_f64)(const void *self, const Particles<double> *p, WallContacts<double> *out);
  void (*contacts_f32)(const void *self, const Particles<float> *p, WallContacts<float> *out);
  double (*max_surface_speed)(const void *self);
  void (*describe)(const void *self, sm_spreader_description_v2 *out);
  void (*pose)(const void *self, double t, sm_spreader_pose_v2 *out);
  // 1 when a sphere (centre, radius) at time t overlaps the body.
  int (*touches)(const void *self, double t, const double centre[3], double radius);
#if SPREADMAP_TARGET_ABI_MINOR >= 3
  // ABI 10.3: the records of particles [lo, hi) only; the host shares the particles between its threads.
  void (*contacts_range_f64)(const void *self, const Particles<double> *p, WallContacts<double> *out, uint32_t lo,
                             uint32_t hi);
  void (*contacts_range_f32)(const void *self, const Particles<float> *p, WallContacts<float> *out, uint32_t lo,
                             uint32_t hi);
#endif
} sm_spreader_ops_v2;
}

// Particle i's dense wall-contact record for this geometry at time p.t. The body of both backends'
// geometry loops.
template <class Geometry, class Real>
SM_HD void geometry_contact_of(const Geometry &g, const Particles<Real> &p, const WallContacts<Real> &w,
                               std::uint32_t i) {
  WallHit<Real> hit{0, {0, 0, 1}, {0, 0, 0}};
  if (g(Vec3<Real>{p.x[i], p.y[i], p.z[i]}, p.r[i], p.t, hit) && hit.overlap > 0) {
    w.overlap[i] = hit.overlap;
    w.nx[i] = hit.normal.x;
    w.ny[i] = hit.normal.y;
    w.nz[i] = hit.normal.z;
    w.vx[i] = hit.velocity.x;
    w.vy[i] = hit.velocity.y;
    w.vz[i] = hit.velocity.z;
  } else {
    w.overlap[i] = 0;
  }
}

// The records of particles [lo, hi).
template <class Geometry, class Real>
void geometry_loop(const Geometry &g, const Particles<Real> &p, WallContacts<Real> &w, std::uint32_t lo,
                   std::uint32_t hi) {
  for (std::uint32_t i = lo; i < hi; ++i) geometry_contact_of(g, p, w, i);
}

namespace detail {
template <class G> struct GeometryOps {
  static const G &geo(const void *s) { return *static_cast<const G *>(s); }
  // every particle (hosts before ABI 10.3), or a range
  template <class Real> static void all(const void *s, const Particles<Real> *p, WallContacts<Real> *w) {
    geometry_loop(geo(s), *p, *w, 0, p->n);
  }
  template <class Real>
  static void range(const void *s, const Particles<Real> *p, WallContacts<Real> *w, uint32_t lo, uint32_t hi) {
    geometry_loop(geo(s), *p, *w, lo, hi);
  }
  static double speed(const void *s) { return geo(s).max_surface_speed(); }
  static void describe(const void *s, sm_spreader_description_v2 *out) {
    *out = sm_spreader_description_v2{};
    geo(s).describe(out);
  }
  static void pose(const void *s, double t, sm_spreader_pose_v2 *out) {
    *out = sm_spreader_pose_v2{};
    geo(s).pose(t, out);
  }
  static int touches(const void *s, double t, const double *c, double radius) {
    WallHit<double> hit{0, {0, 0, 1}, {0, 0, 0}};
    return geo(s)(Vec3<double>{c[0], c[1], c[2]}, radius, t, hit) && hit.overlap > 0 ? 1 : 0;
  }
#if SPREADMAP_TARGET_ABI_MINOR >= 3
  static constexpr sm_spreader_ops_v2 table = {&all<double>, &all<float>, &speed,         &describe,
                                               &pose,        &touches,    &range<double>, &range<float>};
#else
  static constexpr sm_spreader_ops_v2 table = {&all<double>, &all<float>, &speed, &describe, &pose, &touches};
#endif
};
}  // namespace detail
}  // namespace spreadmap

#define SPREADMAP_SPREADER_PLUGIN(GEOMETRY, NAME, VERSION, SUMMARY)                                        \
  static_assert(std::is_trivially_copyable_v<GEOMETRY>, "a spreader geometry must be trivially copyable"); \
  SPREADMAP_PLUGIN("spreader", GEOMETRY, NAME, VERSION, SUMMARY, &::spreadmap::detail::GeometryOps<GEOMETRY>::table)

// A geometry that keeps its data in host memory (a triangle mesh behind a pointer) runs on the CPU
// only: it need not be trivially copyable, and its plugin is built with CPU_ONLY (no GPU kernels).
#define SPREADMAP_SPREADER_PLUGIN_CPU(GEOMETRY, NAME, VERSION, SUMMARY) \
  SPREADMAP_PLUGIN("spreader", GEOMETRY, NAME, VERSION, SUMMARY, &::spreadmap::detail::GeometryOps<GEOMETRY>::table)
