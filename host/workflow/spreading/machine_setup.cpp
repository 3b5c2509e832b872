#include "workflow/spreading/machine_setup.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <limits>

#include "core/error.hpp"
#include "powder/heap.hpp"
#include "workflow/spreading/case_scene.hpp"
#include "workflow/spreading/case_setup.hpp"
#include "workflow/spreading/machine_layout.hpp"
#include "workflow/spreading/powder_sizes.hpp"

namespace spreadmap {

using engine::ParticleSet;

template <class Real>
ParticleSet fill_reservoir(const Scene &scene, PluginRegistry &reg, const std::string &label,
                           const std::filesystem::path &scene_file, const std::function<void(double)> &progress) {
  const Machine &m = *scene.machine;
  const MachineLayout layout = machine_layout(scene);
  const auto sizes = size_distribution(scene.powder);
  const PluginInstance spreader = bind_spreader(scene, reg, scene_file);
  const scene::BoundSpreader at_rest{&spreader, 0.0};
  const double width = scene.domain.width, dmax = sizes.upper();

  powder::HeapSpec spec;
  const double floor = layout.piston_top(0);
  spec.region = {{layout.reservoir_from, 0.0, floor}, {layout.reservoir_to, width, 0.0}};
  spec.periodic_y = true;
  spec.sizes = sizes;
  spec.seed = static_cast<std::uint64_t>(scene.powder.seed);
  spec.solid_volume = reservoir_fill_packing * m.reservoir_length * width * m.reservoir_depth;
  spec.max_top = scene.domain.height - 0.5 * dmax;
  const double clearance = heap_clearance(scene);
  spec.excluded = [&](double x, double y, double z, double r) {
    const double centre[3] = {x, y, z};
    return at_rest.ops().touches(spreader.get(), rest_shift(scene), centre, r + clearance) != 0;
  };
  const powder::Heap heap = powder::insert_heap(spec);
  spdlog::info("{}: {} spheres poured into the reservoir (top {:.2f} mm above the plates), settling", label,
               heap.size(), heap.top * 1e3);

  auto settling = case_scene(scene, scene_file);
  settling.particles.set.x = heap.x;
  settling.particles.set.y = heap.y;
  settling.particles.set.z = heap.z;
  settling.particles.set.radius = heap.r;
  Scene at_start = scene;
  at_start.machine->layer = 0;
  settling.scene.walls = machine_walls(at_start, false);
  settling.scene.walls.push_back(spreader_wall(scene, reg, rest_shift(scene)));
  const ParticleSet settled =
      settle_scene<Real>(settling, reg, powder_settle_rule(scene.powder), label, "reservoir", progress);
  double top = -std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < settled.size(); ++i) top = std::max(top, settled.z[i]);
  if (!(top > -dmax))
    throw InputError(fmt::format(
        "{}: scene.machine: the powder poured into the reservoir settled {:.3g} mm below the plates: it is "
        "not full\n  make the domain taller (domain.height) so that more powder fits above the reservoir while it "
        "is poured",
        scene_file.string(), -top * 1e3));
  ParticleSet level = engine::select_particles(settled, [&](std::size_t i) { return settled.z[i] <= 0.0; });
  spdlog::info("{}: reservoir levelled at the plates: {} spheres ({} taken off the top)", label, level.size(),
               settled.size() - level.size());
  return level;
}

template <class Real>
ParticleSet after_strokes(const Scene &scene, PluginRegistry &reg, const std::string &label,
                          const std::filesystem::path &scene_file, const ParticleSet &bed) {
  const double strokes = stroke_time(scene);
  const SettleRule rule{strokes, strokes + scene.powder.settle_time, scene.powder.settle_speed,
                        scene.powder.settle_fraction};
  auto settling = case_scene(scene, scene_file);
  settling.particles.set = bed;
  settling.scene.walls = machine_walls(scene, true);
  // the spreader rests at its start throughout, however slow the strokes
  settling.scene.walls.push_back(spreader_wall(scene, reg, -(rule.max_time + 1.0)));
  return settle_scene<Real>(settling, reg, rule, label, "powder after the strokes", {});
}

template ParticleSet fill_reservoir<double>(const Scene &, PluginRegistry &, const std::string &,
                                            const std::filesystem::path &, const std::function<void(double)> &);
template ParticleSet fill_reservoir<float>(const Scene &, PluginRegistry &, const std::string &,
                                           const std::filesystem::path &, const std::function<void(double)> &);
template ParticleSet after_strokes<double>(const Scene &, PluginRegistry &, const std::string &,
                                           const std::filesystem::path &, const ParticleSet &);
template ParticleSet after_strokes<float>(const Scene &, PluginRegistry &, const std::string &,
                                          const std::filesystem::path &, const ParticleSet &);

}  // namespace spreadmap
