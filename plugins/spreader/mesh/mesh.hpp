// spreader/mesh: a recoater from CAD. The part's surface is an STL file (a blade, a profiled roller, a
// rubber wiper); it translates at U along +x and may turn at omega about an axis parallel to y that
// the input names (axis_x, axis_z, in the part's own coordinates: a CAD part's centroid is rarely its
// axis). At t = 0 the part is placed with its axis at x = start, its lowest point at z = gap and the
// middle of its extent along y at y = y_centre. Contacts: the nearest point of the surface
// (spreadmap/mesh/triangle_mesh.hpp), with the surface velocity of the rigid motion there.
//
// The mesh lives in host memory, so the plugin runs on the CPU backend only.
#pragma once
#include <spreadmap/geometry.hpp>
#include <spreadmap/mesh/triangle_mesh.hpp>
#include <spreadmap/params.hpp>
#include <spreadmap/spreader/outline.hpp>
#include <spreadmap/spreader/travel.hpp>

#include <memory>
#include <string>

namespace spreadmap::spreader {

struct Mesh {
  static constexpr sm_param_v1 params[] = {
      file_path("file", "the part's surface: an STL file, ASCII or binary (relative to the file that names it)"),
      required_enumeration("unit", "m|cm|mm|um|in", "the STL's length unit: STL files carry none"),
      number("axis_x", "m", -10.0, 10.0, 0.0,
             "x of the part's axis (reference point) in the STL's own coordinates; start places it"),
      number("axis_z", "m", -10.0, 10.0, 0.0, "z of the part's axis in the STL's own coordinates"),
      number("omega", "rad/s", -1e4, 1e4, 0.0,
             "omega: angular velocity about the axis (parallel to +y); > 0 rolls forward, < 0 counter-rotates"),
      number("y_centre", "m", -10.0, 10.0, 0.0,
             "y where the middle of the part's extent along y goes; it must span a periodic strip [0, W]"),
      param_gap("gap between the part's lowest point (at t = 0) and the substrate z = 0"),
      param_speed(),
      param_start("x of the part's axis at t = 0 (time counted from the start of spreading)"),
      param_travel(),
      param_end(),
  };

  std::shared_ptr<const mesh::TriangleMesh> surface;
  Travel travel;
  double axis[3];      // the reference point in the mesh's coordinates [m] (y: the middle of its extent)
  double y_centre;     // where the reference point is along y [m]
  double axis_height;  // and along z [m] (along x: travel.x(t))
  double omega;     // [rad/s]
  double reach;     // largest distance of a vertex from the axis in the x-z plane [m]

  static Mesh bind(const Values &v);

  template <class Real> SM_HD bool operator()(const Vec3<Real> &p, Real r, Real t, WallHit<Real> &hit) const {
    const double time = static_cast<double>(t), angle = omega * travel.elapsed(time);
    const double c = std::cos(angle), s = std::sin(angle);
    // into the part's frame: undo the translation, then the rotation by `angle` about +y
    const double dx = static_cast<double>(p.x) - travel.x(time), dy = static_cast<double>(p.y) - y_centre,
                 dz = static_cast<double>(p.z) - axis_height;
    const mesh::V3 q{c * dx - s * dz + axis[0], dy + axis[1], s * dx + c * dz + axis[2]};
    mesh::SurfacePoint near;
    if (!surface->contact(q, static_cast<double>(r), near)) return false;
    const double overlap = static_cast<double>(r) - near.distance;
    if (!(overlap > 0)) return false;
    // back to the world: rotate the normal; the surface point's velocity is U e_x + omega e_y x arm
    const double nx = c * near.normal.x + s * near.normal.z, nz = -s * near.normal.x + c * near.normal.z;
    const double ax = near.point.x - axis[0], az = near.point.z - axis[2];
    const double arm_x = c * ax + s * az, arm_z = -s * ax + c * az;
    const double w = travel.moving(time) ? omega : 0.0;
    hit.overlap = static_cast<Real>(overlap);
    hit.normal = {static_cast<Real>(nx), static_cast<Real>(near.normal.y), static_cast<Real>(nz)};
    hit.velocity = {static_cast<Real>(travel.velocity(time) + w * arm_z), Real(0), static_cast<Real>(-w * arm_x)};
    return true;
  }

  double max_surface_speed() const { return travel.speed + std::fabs(omega) * reach; }
  void describe(sm_spreader_description_v2 *out) const;
  void pose(double t, sm_spreader_pose_v2 *out) const;
};

}  // namespace spreadmap::spreader
