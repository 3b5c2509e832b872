#include "workflow/spreading/layer_feed.hpp"

#include <algorithm>
#include <functional>
#include <limits>

#include "workflow/spreading/substrate_roughness.hpp"

namespace spreadmap {

using engine::ParticleSet;

double platform_drop(const Scene &scene, int layer) { return double(layer - 1) * scene.layers.thickness; }

Scene layer_scene(const Scene &scene, int layer) {
  Scene out = scene;
  if (out.machine) {  // the platform itself drops
    out.machine->layer = layer;
    return out;
  }
  const double raise = substrate_level(scene) + platform_drop(scene, layer);
  if (raise != 0) out.spreader.params["gap"] = scene.spreader.params["gap"].get<double>() + raise;
  return out;
}

ParticleSet substrate_spheres(const Scene &scene) {
  const auto substrate = rough_substrate_of(scene);
  ParticleSet out;
  if (!substrate) return out;
  out.x = substrate->x;
  out.y = substrate->y;
  out.z = substrate->z;
  out.radius.assign(out.x.size(), substrate->radius);
  out.fixed.assign(out.x.size(), 1);
  for (std::size_t i = 0; i < out.x.size(); ++i) out.id.push_back(std::uint32_t(i));
  return out;
}

namespace {

// An optional column of the bed followed by the kept entries of the heap's: zeros where only one
// set has the column, empty where neither has it.
template <class T>
std::vector<T> joined(const std::vector<T> &bed, std::size_t nb, const std::vector<T> &heap,
                      const std::vector<std::size_t> &kept) {
  if (bed.empty() && heap.empty()) return {};
  std::vector<T> out = bed.empty() ? std::vector<T>(nb, T{}) : bed;
  for (std::size_t i : kept) out.push_back(heap.empty() ? T{} : heap[i]);
  return out;
}

}  // namespace

ParticleSet feed_heap(const ParticleSet &bed, const ParticleSet &heap, double clearance,
                      const std::function<bool(double, double, double, double)> &excluded) {
  double x_lo = std::numeric_limits<double>::max(), x_hi = std::numeric_limits<double>::lowest();
  double bottom = std::numeric_limits<double>::max();
  for (std::size_t i = 0; i < heap.size(); ++i) {
    x_lo = std::min(x_lo, heap.x[i] - heap.radius[i]);
    x_hi = std::max(x_hi, heap.x[i] + heap.radius[i]);
    bottom = std::min(bottom, heap.z[i] - heap.radius[i]);
  }
  double bed_top = 0;  // the substrate where the bed is bare
  for (std::size_t i = 0; i < bed.size(); ++i)
    if (bed.x[i] + bed.radius[i] >= x_lo && bed.x[i] - bed.radius[i] <= x_hi)
      bed_top = std::max(bed_top, bed.z[i] + bed.radius[i]);
  const double lift = heap.size() ? std::max(0.0, bed_top + clearance - bottom) : 0.0;
  ParticleSet lifted = heap;
  for (double &z : lifted.z) z += lift;
  std::vector<std::size_t> kept;
  for (std::size_t i = 0; i < heap.size(); ++i)
    if (!excluded || !excluded(lifted.x[i], lifted.y[i], lifted.z[i], lifted.radius[i])) kept.push_back(i);

  const std::size_t nb = bed.size();
  ParticleSet out;
  out.x = joined(bed.x, nb, lifted.x, kept);
  out.y = joined(bed.y, nb, lifted.y, kept);
  out.z = joined(bed.z, nb, lifted.z, kept);
  out.radius = joined(bed.radius, nb, lifted.radius, kept);
  out.vx = joined(bed.vx, nb, lifted.vx, kept);
  out.vy = joined(bed.vy, nb, lifted.vy, kept);
  out.vz = joined(bed.vz, nb, lifted.vz, kept);
  out.wx = joined(bed.wx, nb, lifted.wx, kept);
  out.wy = joined(bed.wy, nb, lifted.wy, kept);
  out.wz = joined(bed.wz, nb, lifted.wz, kept);
  out.fixed = joined(bed.fixed, nb, lifted.fixed, kept);
  // masses follow from the powder's density unless both sets carry them
  if (bed.mass.size() == nb && heap.mass.size() == heap.size()) out.mass = joined(bed.mass, nb, lifted.mass, kept);
  if (!bed.id.empty() || nb == 0) {
    std::uint32_t next = 0;
    for (auto id : bed.id) next = std::max(next, id + 1);
    out.id = bed.id;
    for (std::size_t i = 0; i < kept.size(); ++i) out.id.push_back(next + std::uint32_t(i));
  }
  return out;
}

}  // namespace spreadmap
