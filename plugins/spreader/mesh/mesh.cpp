// Registers spreader/mesh; binds the part (reads and checks the STL) and describes it for figures.
#include "mesh.hpp"

#include <spreadmap/digest.hpp>

#include <algorithm>
#include <utility>

namespace spreadmap::spreader {
namespace {

// A recoater is millimetres to decimetres: a part outside [0.1 mm, 1 m] is most likely in another unit.
// It is a closed solid across the strip: a part with no extent along y (an outline drawn in the x-z
// plane) would touch nothing but one plane and claim to span every width, and an open surface would
// push a sphere behind it through it (a sphere inside the part could not be told from one behind it).
void check_size(const mesh::TriangleMesh &m, const std::string &file, const std::string &unit) {
  const double extent = m.extent();
  if (!(m.hi()[1] > m.lo()[1]))
    throw ParamError(file + ": the part has no extent along y (all its corners at y = " + text_of(m.lo()[1]) +
                     " m): a recoater is a solid across the strip; export it as one");
  if (!m.closed()) {
    const auto &at = m.open_edge_at();
    throw ParamError(file + ": the part is not closed: " + std::to_string(m.open_edges()) +
                     " edge(s) do not join exactly two triangles (the first at x, y, z = " + text_of(at.x) + ", " +
                     text_of(at.y) + ", " + text_of(at.z) +
                     " m: a hole or a T-junction); export the part as a solid, or repair the mesh");
  }
  if (extent > 1.0 || extent < 1e-4)
    throw ParamError(file + ": the part is " + text_of(extent) + " m across with unit: " + unit +
                     ", implausible for a recoater (0.1 mm to 1 m): most likely the STL is in another unit; "
                     "set unit: to the one it was exported in (m, cm, mm, um or in)");
}

// Andrew's monotone chain: the convex hull of the points, counter-clockwise.
std::vector<std::pair<double, double>> convex_hull(std::vector<std::pair<double, double>> p) {
  std::sort(p.begin(), p.end());
  p.erase(std::unique(p.begin(), p.end()), p.end());
  if (p.size() < 3) return p;
  auto turn = [](const auto &o, const auto &a, const auto &b) {
    return (a.first - o.first) * (b.second - o.second) - (a.second - o.second) * (b.first - o.first);
  };
  std::vector<std::pair<double, double>> hull(2 * p.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    while (k >= 2 && turn(hull[k - 2], hull[k - 1], p[i]) <= 0) --k;
    hull[k++] = p[i];
  }
  for (std::size_t i = p.size() - 1, lower = k + 1; i-- > 0;) {
    while (k >= lower && turn(hull[k - 2], hull[k - 1], p[i]) <= 0) --k;
    hull[k++] = p[i];
  }
  hull.resize(k - 1);
  return hull;
}

}  // namespace

Mesh Mesh::bind(const Values &v) {
  const std::string file = v.str("file"), unit = v.str("unit");
  const double scale = mesh::metres_per(unit);
  if (!(scale > 0)) throw ParamError("unit: give the STL's length unit (m, cm, mm, um or in): STL files carry none");
  const std::string bytes = mesh::read_file_bytes(file);
  if (v.has("file_digest") && content_digest(bytes) != v.str("file_digest"))
    throw ParamError(file + " changed since its scene was validated (digest " + v.str("file_digest") +
                     "): restore it, or run the workflow again: a changed part is a different case");
  auto surface = std::make_shared<const mesh::TriangleMesh>(mesh::read_stl_bytes(bytes, scale, file));
  check_size(*surface, file, unit);
  Mesh m{surface, Travel::bind(v), {}, 0, 0, v["omega"], 0};
  m.axis[0] = v["axis_x"];
  m.axis[1] = 0.5 * (surface->lo()[1] + surface->hi()[1]);
  m.axis[2] = v["axis_z"];
  m.y_centre = v["y_centre"];
  m.axis_height = v["gap"] + (m.axis[2] - surface->lo()[2]);
  for (const auto &p : surface->vertices())
    m.reach = std::max(m.reach, std::hypot(p.x - m.axis[0], p.z - m.axis[2]));
  return m;
}

// The outline is the convex hull of the part's silhouette on the x-z plane (about its axis).
void Mesh::describe(sm_spreader_description_v2 *out) const {
  std::vector<std::pair<double, double>> points;
  for (const auto &p : surface->vertices()) points.emplace_back(p.x - axis[0], p.z - axis[2]);
  const auto hull = convex_hull(std::move(points));
  const std::size_t step = (hull.size() + SM_OUTLINE_MAX - 1) / SM_OUTLINE_MAX;
  for (std::size_t k = 0; k < hull.size(); k += std::max<std::size_t>(step, 1))
    add_vertex(out, hull[k].first, hull[k].second);
  out->y_centre = y_centre;
  out->length = surface->hi()[1] - surface->lo()[1];
  out->turns = omega != 0 ? 1 : 0;
  travel.describe(out);
  out->gap = axis_height - (axis[2] - surface->lo()[2]);
}

void Mesh::pose(double t, sm_spreader_pose_v2 *out) const {
  out->reference[0] = travel.x(t);
  out->reference[1] = y_centre;
  out->reference[2] = axis_height;
  out->angle = omega * travel.elapsed(t);
  out->velocity[0] = travel.velocity(t);
  out->omega = travel.moving(t) ? omega : 0.0;
  out->x_min = omega != 0 ? out->reference[0] - reach : out->reference[0] + surface->lo()[0] - axis[0];
  out->x_max = omega != 0 ? out->reference[0] + reach : out->reference[0] + surface->hi()[0] - axis[0];
}

}  // namespace spreadmap::spreader

SPREADMAP_SPREADER_PLUGIN_CPU(spreadmap::spreader::Mesh, "mesh", "1.0.0",
                              "a part from an STL file (CAD recoater) translating at U along +x, optionally turning")
