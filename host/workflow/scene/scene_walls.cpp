#include "workflow/scene/scene_walls.hpp"

#include <algorithm>
#include <limits>

namespace spreadmap::scene {

std::vector<PlaneOf> planes_of(const WallSpec &w) {
  if (w.kind == WallKind::plane) return {{w.point, w.normal, w.name}};
  if (w.kind != WallKind::box) return {};
  std::vector<PlaneOf> out;
  static const char *faces[3][2] = {{"x lo", "x hi"}, {"y lo", "y hi"}, {"z lo", "z hi"}};
  for (int a = 0; a < 3; ++a) {
    Vec n{0, 0, 0};
    n[a] = 1;
    out.push_back({w.lo, n, w.name + " " + faces[a][0]});
    if (a == 2 && w.open_top) continue;
    n[a] = -1;
    out.push_back({w.hi, n, w.name + " " + faces[a][1]});
  }
  return out;
}

double wall_overlap(const WallSpec &w, const Vec &c, double r) {
  if (w.kind == WallKind::cylinder) {
    const CylinderWall &cyl = w.cylinder;
    const Vec3<double> a{cyl.axis[0], cyl.axis[1], cyl.axis[2]};
    const Vec3<double> q{c[0] - cyl.base[0], c[1] - cyl.base[1], c[2] - cyl.base[2]};
    const double h = dot(q, a);
    if (cyl.inside) {
      const double d = norm(q - a * h);
      if (h < 0 || h > cyl.height) return -std::numeric_limits<double>::infinity();
      // inside: how far it reaches past the surface; outside (the tube ignores it): how far into it
      return d < cyl.radius ? r + d - cyl.radius : r - (d - cyl.radius);
    }
    WallHit<double> hit{0, {0, 0, 1}, {0, 0, 0}};
    if (cyl(Vec3<double>{c[0], c[1], c[2]}, r, 0.0, hit)) return hit.overlap;
    return 0;  // apart (or exactly on the axis inside the body, which the geometry cannot orient)
  }
  if (w.kind == WallKind::block) {
    WallHit<double> hit{0, {0, 0, 1}, {0, 0, 0}};
    return block_of(w)(Vec3<double>{c[0], c[1], c[2]}, r, 0.0, hit) ? hit.overlap : 0;
  }
  double deepest = -std::numeric_limits<double>::infinity();
  for (const auto &p : planes_of(w)) {
    const double s =
        (c[0] - p.point[0]) * p.normal[0] + (c[1] - p.point[1]) * p.normal[1] + (c[2] - p.point[2]) * p.normal[2];
    deepest = std::max(deepest, r - s);
  }
  return deepest;
}

}  // namespace spreadmap::scene
