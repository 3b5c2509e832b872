// Building a spreader's cross-section for its description (sm_spreader_description_v2): polygons
// in the x–z plane of the body frame, counter-clockwise. Host only.
#pragma once
#include <spreadmap/geometry.hpp>

#include <cmath>

namespace spreadmap::spreader {

// Appends the vertex (x, z), silently dropping it when the outline is full.
inline void add_vertex(sm_spreader_description_v2 *out, double x, double z) {
  if (out->vertices >= SM_OUTLINE_MAX) return;
  out->x[out->vertices] = x;
  out->z[out->vertices] = z;
  ++out->vertices;
}

// Appends `segments` + 1 points of the arc of radius r about (cx, cz) from angle a0 to a1 (radians,
// counted from +x towards +z). r = 0 appends the centre once.
inline void add_arc(sm_spreader_description_v2 *out, double cx, double cz, double r, double a0, double a1,
                    int segments) {
  if (!(r > 0)) return add_vertex(out, cx, cz);
  for (int k = 0; k <= segments; ++k) {
    const double a = a0 + (a1 - a0) * k / segments;
    add_vertex(out, cx + r * std::cos(a), cz + r * std::sin(a));
  }
}

// A circle of radius r about the origin, as `segments` vertices.
inline void add_circle(sm_spreader_description_v2 *out, double r, int segments) {
  constexpr double two_pi = 6.283185307179586;
  for (int k = 0; k < segments; ++k)
    add_vertex(out, r * std::cos(two_pi * k / segments), r * std::sin(two_pi * k / segments));
}

}  // namespace spreadmap::spreader
