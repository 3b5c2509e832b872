// A rigid triangle mesh as a wall: for a sphere centre, the nearest point of the surface, the signed
// distance to it and the normal there. Host only (the mesh lives in host memory).
//
// One contact per sphere and mesh, with the nearest feature (face, edge or corner), as the analytic
// spreaders have one contact with their nearest surface point. The distance to a mesh is continuous,
// so a sphere rolling across the shared edge of two coplanar triangles feels no jump, and a contact is
// never counted twice. Inside or outside is told by the feature's pseudo-normal (Baerentzen and
// Aanaes 2005): the face normal, the sum of the two faces' normals at an edge, the angle-weighted
// sum at a corner; for a closed mesh this is the exact sign, and an open mesh (a plate) is a
// one-sided wall whose faces point to the particles. A centre deeper inside a closed part than its
// own radius (a sphere placed inside it) is found by casting a ray (inside()) and pushed out
// through the nearest surface; an open mesh has no inside (closed(): every edge shared by exactly
// two triangles; a T-junction counts as open).
//
// Triangles are binned in a uniform grid over the mesh's box: a query visits only the cells its
// sphere overlaps, so a sphere far from the mesh costs one box test whatever the mesh's size.
#pragma once
#include <spreadmap/mesh/closest_point.hpp>
#include <spreadmap/mesh/stl.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <utility>
#include <vector>

namespace spreadmap::mesh {

using V3 = Vec3<double>;

struct SurfacePoint {
  double distance;  // signed: < 0 when the centre is inside [m]
  V3 normal;        // unit, from the surface towards the outside (into a touching sphere)
  V3 point;         // the nearest surface point [m]
};

class TriangleMesh {
 public:
  explicit TriangleMesh(const std::vector<Triangle> &triangles) {
    weld(triangles);
    pseudo_normals();
    bin();
    if (closed()) flag_empty_cells();
  }

  // The nearest surface point to `p` when one lies within `reach`; `examined` counts the triangle
  // tests made (for the binning's tests).
  bool nearest(const V3 &p, double reach, SurfacePoint &out, std::size_t *examined = nullptr) const {
    std::int64_t from[3], to[3];
    const double q[3] = {p.x, p.y, p.z};
    for (int d = 0; d < 3; ++d) {
      if (!(q[d] + reach >= lo_[d] && q[d] - reach <= hi_[d])) return false;  // (NaN: outside)
      from[d] = std::clamp<std::int64_t>(static_cast<std::int64_t>(std::floor((q[d] - reach - lo_[d]) / cell_)), 0,
                                         dims_[d] - 1);
      to[d] = std::clamp<std::int64_t>(static_cast<std::int64_t>(std::floor((q[d] + reach - lo_[d]) / cell_)), 0,
                                       dims_[d] - 1);
    }
    double best = reach * reach;
    std::uint32_t best_t = 0;
    ClosestPoint best_c{};
    bool found = false;
    for (std::int64_t i = from[0]; i <= to[0]; ++i)
      for (std::int64_t j = from[1]; j <= to[1]; ++j)
        for (std::int64_t k = from[2]; k <= to[2]; ++k) {
          const std::size_t cell = static_cast<std::size_t>((i * dims_[1] + j) * dims_[2] + k);
          for (std::uint32_t s = cell_start_[cell]; s < cell_start_[cell + 1]; ++s) {
            const std::uint32_t t = cell_items_[s];
            if ((found && t == best_t) || !(box_distance2(t, q) <= best)) continue;  // seen, or too far
            const auto &c = corner_[t];
            const ClosestPoint cp = closest_point_on_triangle(p, vertex_[c[0]], vertex_[c[1]], vertex_[c[2]]);
            const V3 v = p - cp.point;
            const double d2 = dot(v, v);
            if (examined) ++*examined;
            if (d2 < best || (!found && d2 <= best)) {
              best = d2, best_t = t, best_c = cp, found = true;
            }
          }
        }
    if (!found) return false;
    out = signed_point(p, best_t, best_c);
    return true;
  }

  // The surface point a sphere of radius `reach` at `p` touches: the nearest within reach, or, when
  // `p` lies inside a closed part deeper than that, the nearest at any distance.
  bool contact(const V3 &p, double reach, SurfacePoint &out, std::size_t *examined = nullptr) const {
    if (nearest(p, reach, out, examined)) return true;
    if (!inside(p)) return false;
    for (double r = std::max(2 * reach, cell_); r < 4 * extent(); r *= 2)
      if (nearest(p, r, out, examined)) return true;
    return nearest(p, 4 * extent(), out, examined);
  }

  // Whether `p` lies inside the closed part: the parity of the surface crossings of the ray from p
  // towards +z. A cell no triangle reaches lies wholly on one side (its flag, taken at build); in
  // another cell the ray is cast, each crossing counted in the cell that holds it, and a ray through
  // an edge or corner shared by two triangles is counted once (the top-left rule of rasterisers).
  bool inside(const V3 &p) const {
    if (!closed()) return false;
    const double q[3] = {p.x, p.y, p.z};
    std::int64_t c[3];
    for (int d = 0; d < 3; ++d) {
      if (!(q[d] >= lo_[d] && q[d] <= hi_[d])) return false;
      c[d] = std::min<std::int64_t>(static_cast<std::int64_t>((q[d] - lo_[d]) / cell_), dims_[d] - 1);
    }
    const std::size_t cell = static_cast<std::size_t>((c[0] * dims_[1] + c[1]) * dims_[2] + c[2]);
    if (cell_start_[cell] == cell_start_[cell + 1]) return empty_inside_[cell] != 0;
    bool odd = false;
    for (std::int64_t k = c[2]; k < dims_[2]; ++k) {
      const std::size_t at = static_cast<std::size_t>((c[0] * dims_[1] + c[1]) * dims_[2] + k);
      const double z0 = k == c[2] ? p.z : lo_[2] + static_cast<double>(k) * cell_;
      const double z1 = k + 1 == dims_[2] ? hi_[2] + cell_ : lo_[2] + static_cast<double>(k + 1) * cell_;
      for (std::uint32_t s = cell_start_[at]; s < cell_start_[at + 1]; ++s) {
        double z;
        if (crossing(cell_items_[s], p.x, p.y, z) && z > z0 && z <= z1) odd = !odd;
      }
    }
    return odd;
  }

  const std::array<double, 3> &lo() const { return lo_; }
  const std::array<double, 3> &hi() const { return hi_; }
  // The largest side of the mesh's box [m].
  double extent() const { return std::max({hi_[0] - lo_[0], hi_[1] - lo_[1], hi_[2] - lo_[2]}); }
  const std::vector<V3> &vertices() const { return vertex_; }
  std::size_t triangles() const { return corner_.size(); }
  bool closed() const { return open_edges_ == 0; }
  // Edges that do not belong to exactly two triangles (a hole's rim, a T-junction), and one of them.
  std::size_t open_edges() const { return open_edges_; }
  const V3 &open_edge_at() const { return open_edge_at_; }

 private:
  SurfacePoint signed_point(const V3 &p, std::uint32_t t, const ClosestPoint &cp) const {
    if (cp.feature == Feature::face) {  // the plane's signed distance, as an analytic plane has it
      const V3 &n = face_normal_[t];
      return {dot(p - vertex_[corner_[t][0]], n), n, cp.point};
    }
    const V3 pseudo = cp.feature <= Feature::edge2 ? edge_normal_[t][static_cast<int>(cp.feature) - 1]
                                                   : vertex_normal_[corner_[t][static_cast<int>(cp.feature) - 4]];
    const V3 v = p - cp.point;
    const double length = norm(v);
    if (!(length > 0)) return {0.0, pseudo * (1 / norm(pseudo)), cp.point};
    const double side = dot(v, pseudo) < 0 ? -1.0 : 1.0;
    return {side * length, v * (side / length), cp.point};
  }

  // Squared distance from q to triangle t's box: a triangle whose box is farther than the nearest
  // point found so far cannot hold a nearer one.
  double box_distance2(std::uint32_t t, const double q[3]) const {
    double d2 = 0;
    for (int d = 0; d < 3; ++d) {
      const double below = box_[t][d] - q[d], above = q[d] - box_[t][d + 3];
      const double out = below > 0 ? below : above > 0 ? above : 0.0;
      d2 += out * out;
    }
    return d2;
  }

  // Corners that coincide exactly become one vertex: what tells edges and corners apart.
  void weld(const std::vector<Triangle> &triangles) {
    std::map<Point, std::uint32_t> index;
    for (const Triangle &tri : triangles) {
      std::array<std::uint32_t, 3> c{};
      for (int k = 0; k < 3; ++k) {
        const auto [it, added] = index.emplace(tri.corner[k], static_cast<std::uint32_t>(vertex_.size()));
        if (added) vertex_.push_back({tri.corner[k][0], tri.corner[k][1], tri.corner[k][2]});
        c[k] = it->second;
      }
      corner_.push_back(c);
      const V3 n = cross(vertex_[c[1]] - vertex_[c[0]], vertex_[c[2]] - vertex_[c[0]]);
      face_normal_.push_back(n * (1 / norm(n)));
    }
  }

  void pseudo_normals() {
    std::map<std::pair<std::uint32_t, std::uint32_t>, V3> edge_sum;
    std::map<std::pair<std::uint32_t, std::uint32_t>, int> edge_faces;
    vertex_normal_.assign(vertex_.size(), V3{0, 0, 0});
    for (std::size_t t = 0; t < corner_.size(); ++t)
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t a = corner_[t][k], b = corner_[t][(k + 1) % 3], c = corner_[t][(k + 2) % 3];
        edge_sum[std::minmax(a, b)] += face_normal_[t];
        ++edge_faces[std::minmax(a, b)];
        const V3 u = vertex_[b] - vertex_[a], w = vertex_[c] - vertex_[a];
        const double angle = std::acos(std::clamp(dot(u, w) / (norm(u) * norm(w)), -1.0, 1.0));
        vertex_normal_[a] += face_normal_[t] * angle;
      }
    for (const auto &[edge, faces] : edge_faces)
      if (faces != 2 && open_edges_++ == 0) open_edge_at_ = vertex_[edge.first];
    edge_normal_.resize(corner_.size());
    for (std::size_t t = 0; t < corner_.size(); ++t)
      for (int k = 0; k < 3; ++k) edge_normal_[t][k] = edge_sum[std::minmax(corner_[t][k], corner_[t][(k + 1) % 3])];
  }

  // Cells about as wide as the median triangle (and at most 2^20 of them); each lists the triangles
  // whose box overlaps it.
  void bin() {
    lo_ = {vertex_[0].x, vertex_[0].y, vertex_[0].z};
    hi_ = lo_;
    for (const V3 &v : vertex_) {
      const double c[3] = {v.x, v.y, v.z};
      for (int d = 0; d < 3; ++d) lo_[d] = std::min(lo_[d], c[d]), hi_[d] = std::max(hi_[d], c[d]);
    }
    // A triangle's middle box extent is its width: a long strip (a cylinder's facet) crosses many cells
    // along its length but stays one cell wide.
    box_.resize(corner_.size());
    std::vector<double> width(corner_.size());
    for (std::size_t t = 0; t < corner_.size(); ++t) {
      for (int d = 0; d < 3; ++d) {
        const double c0 = coord(corner_[t][0], d), c1 = coord(corner_[t][1], d), c2 = coord(corner_[t][2], d);
        box_[t][d] = std::min({c0, c1, c2}), box_[t][d + 3] = std::max({c0, c1, c2});
      }
      std::array<double, 3> e{box_[t][3] - box_[t][0], box_[t][4] - box_[t][1], box_[t][5] - box_[t][2]};
      std::sort(e.begin(), e.end());
      width[t] = e[1];
    }
    std::nth_element(width.begin(), width.begin() + static_cast<std::ptrdiff_t>(width.size() / 2), width.end());
    const double typical = width[width.size() / 2];
    cell_ = std::max(typical, extent() / 1024);
    for (;;) {
      std::size_t cells = 1;
      for (int d = 0; d < 3; ++d) {
        dims_[d] = std::max<std::int64_t>(1, static_cast<std::int64_t>(std::ceil((hi_[d] - lo_[d]) / cell_)));
        cells *= static_cast<std::size_t>(dims_[d]);
      }
      if (cells <= (std::size_t(1) << 20)) break;
      cell_ *= 1.25;
    }
    const double pad = 1e-9 * extent();
    std::vector<std::vector<std::uint32_t>> lists(static_cast<std::size_t>(dims_[0] * dims_[1] * dims_[2]));
    for (std::size_t t = 0; t < corner_.size(); ++t) {
      std::int64_t from[3], to[3];
      for (int d = 0; d < 3; ++d) {
        from[d] = std::clamp<std::int64_t>(
            static_cast<std::int64_t>(std::floor((box_[t][d] - pad - lo_[d]) / cell_)), 0, dims_[d] - 1);
        to[d] = std::clamp<std::int64_t>(
            static_cast<std::int64_t>(std::floor((box_[t][d + 3] + pad - lo_[d]) / cell_)), 0, dims_[d] - 1);
      }
      for (std::int64_t i = from[0]; i <= to[0]; ++i)
        for (std::int64_t j = from[1]; j <= to[1]; ++j)
          for (std::int64_t k = from[2]; k <= to[2]; ++k)
            lists[static_cast<std::size_t>((i * dims_[1] + j) * dims_[2] + k)].push_back(
                static_cast<std::uint32_t>(t));
    }
    cell_start_.assign(1, 0);
    for (const auto &l : lists) {
      cell_items_.insert(cell_items_.end(), l.begin(), l.end());
      cell_start_.push_back(static_cast<std::uint32_t>(cell_items_.size()));
    }
  }

  // Where the vertical line through (x, y) meets triangle t (z), when it does; every point of the
  // plane counted by exactly one of the triangles that share an edge or a corner there.
  bool crossing(std::uint32_t t, double x, double y, double &z) const {
    V3 a = vertex_[corner_[t][0]], b = vertex_[corner_[t][1]], c = vertex_[corner_[t][2]];
    const double area = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
    if (area == 0) return false;  // seen edge-on from above
    if (area < 0) std::swap(b, c);
    auto covers = [x, y](const V3 &u, const V3 &v) {
      const double e = (v.x - u.x) * (y - u.y) - (v.y - u.y) * (x - u.x);
      return e > 0 || (e == 0 && (v.y < u.y || (v.y == u.y && v.x < u.x)));
    };
    if (!covers(a, b) || !covers(b, c) || !covers(c, a)) return false;
    const V3 &n = face_normal_[t];
    if (n.z == 0) return false;
    z = a.z - (n.x * (x - a.x) + n.y * (y - a.y)) / n.z;
    return true;
  }

  // Each empty cell's side, by the same ray from its column's centre: the crossings of the column's
  // triangles above each cell centre (each crossing counted in the cell that holds it).
  void flag_empty_cells() {
    empty_inside_.assign(cell_start_.size() - 1, 0);
    std::vector<double> hits;
    for (std::int64_t i = 0; i < dims_[0]; ++i)
      for (std::int64_t j = 0; j < dims_[1]; ++j) {
        const double x = lo_[0] + (static_cast<double>(i) + 0.5) * cell_, y = lo_[1] + (static_cast<double>(j) + 0.5) * cell_;
        hits.clear();
        for (std::int64_t k = 0; k < dims_[2]; ++k) {
          const std::size_t at = static_cast<std::size_t>((i * dims_[1] + j) * dims_[2] + k);
          const double z0 = lo_[2] + static_cast<double>(k) * cell_;
          const double z1 = k + 1 == dims_[2] ? hi_[2] + cell_ : z0 + cell_;
          for (std::uint32_t s = cell_start_[at]; s < cell_start_[at + 1]; ++s) {
            double z;
            if (crossing(cell_items_[s], x, y, z) && z > z0 && z <= z1) hits.push_back(z);
          }
        }
        for (std::int64_t k = 0; k < dims_[2]; ++k) {
          const std::size_t at = static_cast<std::size_t>((i * dims_[1] + j) * dims_[2] + k);
          if (cell_start_[at] != cell_start_[at + 1]) continue;
          const double centre = lo_[2] + (static_cast<double>(k) + 0.5) * cell_;
          std::size_t above = 0;
          for (double z : hits) above += z > centre ? 1 : 0;
          empty_inside_[at] = above % 2 ? 1 : 0;
        }
      }
  }

  double coord(std::uint32_t v, int d) const { return d == 0 ? vertex_[v].x : d == 1 ? vertex_[v].y : vertex_[v].z; }

  std::vector<V3> vertex_;
  std::vector<std::array<std::uint32_t, 3>> corner_;
  std::vector<V3> face_normal_;
  std::vector<std::array<V3, 3>> edge_normal_;
  std::vector<std::array<double, 6>> box_;  // per triangle: its box, lo then hi  // per triangle, edge k from corner k to corner k + 1
  std::vector<V3> vertex_normal_;
  std::array<double, 3> lo_{}, hi_{};
  double cell_ = 1;
  std::int64_t dims_[3] = {1, 1, 1};
  std::vector<std::uint32_t> cell_start_, cell_items_;
  std::vector<unsigned char> empty_inside_;  // per cell: 1 when it holds no triangle and lies inside
  std::size_t open_edges_ = 0;  // edges not shared by exactly two triangles
  V3 open_edge_at_{0, 0, 0};     // a corner of the first of them
};

}  // namespace spreadmap::mesh
