#include "workflow/spreading/case_setup.hpp"

#include <spdlog/spdlog.h>
#include <spreadmap/contact.hpp>
#include <spreadmap/geometry.hpp>

#include <cmath>
#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "core/stop.hpp"
#include "powder/heap.hpp"
#include "workflow/spreading/case_scene.hpp"
#include "workflow/spreading/layer_feed.hpp"
#include "workflow/spreading/machine_layout.hpp"
#include "workflow/spreading/machine_setup.hpp"
#include "workflow/spreading/powder_sizes.hpp"

namespace spreadmap {

using engine::ParticleSet;

PluginInstance bind_spreader(const Scene &scene, PluginRegistry &reg, const fs::path &scene_file) {
  return PluginInstance(reg.get("spreader", scene.spreader.use), scene.spreader.params.dump(),
                        scene_file.string() + ": scene.spreader");
}

nlohmann::json to_json(const sm_spreader_description_v2 &d) {
  return {{"outline_x", std::vector<double>(d.x, d.x + d.vertices)},
          {"outline_z", std::vector<double>(d.z, d.z + d.vertices)},
          {"y_centre", d.y_centre},
          {"length", d.length},
          {"turns", d.turns != 0},
          {"start", d.start},
          {"end", d.end},
          {"speed", d.speed},
          {"duration", d.duration},
          {"gap", d.gap}};
}

nlohmann::json to_json(const sm_spreader_pose_v2 &p) {
  return {{"reference", {p.reference[0], p.reference[1], p.reference[2]}},
          {"angle", p.angle},
          {"velocity", {p.velocity[0], p.velocity[1], p.velocity[2]}},
          {"omega", p.omega},
          {"x_min", p.x_min},
          {"x_max", p.x_max}};
}

sm_spreader_description_v2 describe_spreader(const Scene &scene, PluginRegistry &reg, const fs::path &scene_file) {
  const PluginInstance spreader = bind_spreader(scene, reg, scene_file);
  return scene::BoundSpreader{&spreader, 0.0}.description();
}

engine::Domain make_domain(const Scene &scene) {
  const SpreadingBox &d = scene.domain;
  engine::Domain dom;
  dom.lo = {0, 0, scene.machine ? machine_layout(scene).bottom : 0.0};
  dom.hi = {d.length, d.width, d.height};
  dom.periodic = {d.periodic_x, d.periodic_y, false};
  return dom;
}

scene::LoadedScene spreading_scene(const Scene &spreading, const ParticleSet &heap, const fs::path &scene_file) {
  auto l = case_scene(spreading, scene_file);
  if (spreading.machine) l.scene.walls = machine_walls(spreading, false);
  else l.scene.walls = {plane_wall("substrate", "scene.substrate", {0, 0, 0}, {0, 0, 1}, spreading.substrate.law)};
  l.particles.set = heap;
  return l;
}

template <class Real>
ParticleSet settle_heap(const Scene &scene, PluginRegistry &reg, const std::string &label, const fs::path &scene_file,
                        const std::function<void(double)> &progress) {
  if (scene.machine) return fill_reservoir<Real>(scene, reg, label, scene_file, progress);
  const Powder &powder = scene.powder;
  const auto dom = make_domain(scene);
  const PluginInstance spreader = bind_spreader(scene, reg, scene_file);
  const scene::BoundSpreader at_rest{&spreader, 0.0};
  const double t_settle = powder.settle_time;

  powder::HeapSpec spec;
  const auto sizes = size_distribution(powder);
  const double dmax = sizes.upper();
  const double top = powder.heap_top > 0 ? powder.heap_top : dom.hi[2] - dmax;
  spec.region = {{powder.heap_from, dom.lo[1], 0.0}, {powder.heap_to, dom.hi[1], top}};
  spec.periodic_y = dom.periodic[1];
  spec.sizes = sizes;
  spec.seed = static_cast<std::uint64_t>(powder.seed);
  if (powder.volume > 0) spec.solid_volume = powder.volume;
  else spec.count = static_cast<std::size_t>(powder.count);
  spec.max_top = dom.hi[2] - 0.5 * dmax;
  const double clearance = heap_clearance(scene);
  spec.excluded = [&](double x, double y, double z, double r) {
    const double centre[3] = {x, y, z};
    return at_rest.ops().touches(spreader.get(), rest_shift(scene), centre, r + clearance) != 0;
  };
  const powder::Heap heap = powder::insert_heap(spec);
  spdlog::info("{}: heap of {} spheres inserted (top {:.2f} mm), settling {:.3g} s", label, heap.size(), heap.top * 1e3,
               t_settle);

  // The settling scene: the heap between two temporary walls (the spreader's law), the spreader at rest.
  auto settling = case_scene(scene, scene_file);
  settling.particles.set.x = heap.x;
  settling.particles.set.y = heap.y;
  settling.particles.set.z = heap.z;
  settling.particles.set.radius = heap.r;
  const auto &wall_law = scene.spreader.law;
  settling.scene.walls = {plane_wall("substrate", "scene.substrate", {0, 0, 0}, {0, 0, 1}, scene.substrate.law),
                          plane_wall("heap back wall", "scene.spreader", {spec.region.lo[0], 0, 0}, {1, 0, 0}, wall_law),
                          plane_wall("heap front wall", "scene.spreader", {spec.region.hi[0], 0, 0}, {-1, 0, 0}, wall_law),
                          spreader_wall(scene, reg, rest_shift(scene))};
  return settle_scene<Real>(settling, reg, powder_settle_rule(scene.powder), label, "heap", progress);
}

ParticleSet fed_onto_bed(const Scene &scene, PluginRegistry &reg, const fs::path &scene_file, const ParticleSet &bed,
                         const ParticleSet &heap) {
  const PluginInstance spreader = bind_spreader(scene, reg, scene_file);
  const scene::BoundSpreader at_rest{&spreader, 0.0};
  auto touches = [&](double x, double y, double z, double r) {
    const double centre[3] = {x, y, z};
    return at_rest.ops().touches(spreader.get(), rest_shift(scene), centre, r) != 0;
  };
  std::size_t touching = 0;
  for (std::size_t i = 0; i < bed.size(); ++i) touching += touches(bed.x[i], bed.y[i], bed.z[i], bed.radius[i]);
  if (touching)
    throw InputError(
        fmt::format("{}: scene.layers.thickness: {} spheres of the bed touch the spreader at its "
                    "start, raised by the platform's drop\n  use thicker layers or a larger gap",
                    scene_file.string(), touching));
  const double clearance = heap_clearance(scene);
  ParticleSet fed = feed_heap(bed, heap, clearance,
                              [&](double x, double y, double z, double r) { return touches(x, y, z, r + clearance); });
  double top = 0;
  for (std::size_t i = bed.size(); i < fed.size(); ++i) top = std::max(top, fed.z[i] + fed.radius[i]);
  if (top > scene.domain.height)
    throw InputError(fmt::format("{}: scene.layers: the heap fed onto the bed reaches z = {:.3g} mm, above the "
                                 "domain's height {:.3g} mm\n  make the domain taller (domain.height) or let the heap "
                                 "settle longer (powder.settle_time)",
                                 scene_file.string(), top * 1e3, scene.domain.height * 1e3));
  return fed;
}

template <class Real>
ParticleSet settle_on_bed(const Scene &scene, PluginRegistry &reg, const std::string &label, const fs::path &scene_file,
                          const ParticleSet &fed, const std::function<void(double)> &progress) {
  auto settling = case_scene(scene, scene_file);
  settling.particles.set = fed;
  settling.scene.walls = {plane_wall("substrate", "scene.substrate", {0, 0, 0}, {0, 0, 1}, scene.substrate.law),
                          spreader_wall(scene, reg, rest_shift(scene))};
  return settle_scene<Real>(settling, reg, powder_settle_rule(scene.powder), label, "heap fed onto the bed",
                            progress);
}

template <class Real>
std::unique_ptr<SpreadingRun<Real>> make_spreading_run(const Scene &scene, PluginRegistry &reg, const ParticleSet &heap,
                                                       const fs::path &scene_file) {
  auto l = spreading_scene(scene, heap, scene_file);
  l.scene.walls.push_back(spreader_wall(scene, reg, 0.0));
  auto built = scene::build_scene<Real>(l, reg);
  auto &sim = *built->sim;
  const auto &spreader = built->spreaders.front();
  return std::unique_ptr<SpreadingRun<Real>>(new SpreadingRun<Real>{std::move(built), sim, spreader});
}

template <class Real>
bool run_spreading(engine::Simulation<Real> &sim, const scene::BoundSpreader &spreader, const Scene &spreading,
                   double t_end, const typename engine::Simulation<Real>::StepCallback &callback, std::uint64_t every) {
  const bool sleep = spreading.time.sleep;
  const double behind = spreading.time.sleep_behind, buried = sleep_below(spreading);
  auto follow = [&] {
    if (!sleep) return;
    sim.set_sleep_region(spreader.pose(sim.time()).x_min - behind, buried);  // behind its trailing edge, or deep
  };
  follow();
  return sim.run_until(
      t_end,
      [&](const engine::Simulation<Real> &s) {
        follow();
        return !callback || callback(s);
      },
      every);
}

template ParticleSet settle_heap<double>(const Scene &, PluginRegistry &, const std::string &, const fs::path &,
                                         const std::function<void(double)> &);
template ParticleSet settle_heap<float>(const Scene &, PluginRegistry &, const std::string &, const fs::path &,
                                        const std::function<void(double)> &);
template ParticleSet settle_on_bed<double>(const Scene &, PluginRegistry &, const std::string &, const fs::path &,
                                           const ParticleSet &, const std::function<void(double)> &);
template ParticleSet settle_on_bed<float>(const Scene &, PluginRegistry &, const std::string &, const fs::path &,
                                          const ParticleSet &, const std::function<void(double)> &);
template struct SpreadingRun<double>;
template struct SpreadingRun<float>;
template std::unique_ptr<SpreadingRun<double>> make_spreading_run<double>(const Scene &, PluginRegistry &,
                                                                          const ParticleSet &, const fs::path &);
template std::unique_ptr<SpreadingRun<float>> make_spreading_run<float>(const Scene &, PluginRegistry &,
                                                                        const ParticleSet &, const fs::path &);
template bool run_spreading<double>(engine::Simulation<double> &, const scene::BoundSpreader &, const Scene &,
                                    double, const engine::Simulation<double>::StepCallback &, std::uint64_t);
template bool run_spreading<float>(engine::Simulation<float> &, const scene::BoundSpreader &, const Scene &,
                                   double, const engine::Simulation<float>::StepCallback &, std::uint64_t);

}  // namespace spreadmap
