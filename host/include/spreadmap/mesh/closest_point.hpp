// The point of a triangle closest to a point, and which feature it lies on (the face's interior,
// one of its edges, one of its corners): the feature decides which normal tells inside from outside
// (mesh/triangle_mesh.hpp). Region tests on barycentric coordinates, in the order of Ericson's
// Real-Time Collision Detection, section 5.1.5.
#pragma once
#include <spreadmap/hd.hpp>

namespace spreadmap::mesh {

// corner k: the triangle's corner k; edge k: the edge from corner k to corner (k + 1) % 3.
enum class Feature : unsigned char { face, edge0, edge1, edge2, corner0, corner1, corner2 };

struct ClosestPoint {
  Vec3<double> point;
  Feature feature;
};

inline ClosestPoint closest_point_on_triangle(const Vec3<double> &p, const Vec3<double> &a, const Vec3<double> &b,
                                              const Vec3<double> &c) {
  const Vec3<double> ab = b - a, ac = c - a, ap = p - a;
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) return {a, Feature::corner0};
  const Vec3<double> bp = p - b;
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return {b, Feature::corner1};
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return {a + ab * (d1 / (d1 - d3)), Feature::edge0};
  const Vec3<double> cp = p - c;
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return {c, Feature::corner2};
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return {a + ac * (d2 / (d2 - d6)), Feature::edge2};
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
    return {b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6))), Feature::edge1};
  const double denom = 1 / (va + vb + vc);
  return {a + ab * (vb * denom) + ac * (vc * denom), Feature::face};
}

}  // namespace spreadmap::mesh
