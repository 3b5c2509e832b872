#include "workflow/simulate/case_setup.hpp"

#ifdef SPREADMAP_WITH_CUDA
#include "cuda/backend.hpp"
#include "cuda/resident_stepper.hpp"
#endif

#include <spdlog/spdlog.h>
#include <spreadmap/contact.hpp>
#include <spreadmap/geometry.hpp>

#include <cmath>

#include "core/error.hpp"
#include "core/stop.hpp"
#include "scene/heap.hpp"
#include "workflow/scene/powder_sizes.hpp"

namespace spreadmap {

using engine::ParticleSet;

CasePlugins::CasePlugins(const Scene &scene, PluginRegistry &reg, const fs::path &scene_file) {
  const auto &law = reg.get("contact", scene.contact.use);
  const auto &geo = reg.get("spreader", scene.spreader.use);
  const std::string at = scene_file.string() + ": ";
  pair = PluginInstance(law, scene.contact.params.dump(), at + "scene.contact");
  substrate = PluginInstance(law, scene.substrate.law.dump(), at + "scene.substrate");
  spreader_law = PluginInstance(law, scene.spreader.law.dump(), at + "scene.spreader");
  spreader = PluginInstance(geo, scene.spreader.params.dump(), at + "scene.spreader");
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

engine::ContactLaw CasePlugins::law(const PluginInstance &i) const { return {i.ops<sm_contact_ops_v1>(), i.get()}; }

sm_spreader_description_v2 CasePlugins::spreader_description() const {
  sm_spreader_description_v2 d{};
  spreader_ops().describe(spreader.get(), &d);
  return d;
}

sm_spreader_pose_v2 CasePlugins::spreader_pose(double t) const {
  sm_spreader_pose_v2 pose{};
  spreader_ops().pose(spreader.get(), t, &pose);
  return pose;
}

sm_spreader_description_v2 describe_spreader(const Scene &scene, PluginRegistry &reg, const fs::path &scene_file) {
  const auto &geo = reg.get("spreader", scene.spreader.use);
  const PluginInstance spreader(geo, scene.spreader.params.dump(), scene_file.string() + ": scene.spreader");
  sm_spreader_description_v2 d{};
  spreader.ops<sm_spreader_ops_v2>()->describe(spreader.get(), &d);
  return d;
}

namespace {
// Adds a plane wall whose law is the plugin `law`, and keeps the plugin: the GPU backend needs the
// kernels of every plane's law, in the order the walls were added.
template <class Real>
void add_plane(engine::Simulation<Real> &sim, std::vector<const PluginInstance *> &plane_laws,
               const CasePlugins &plugins, const std::array<double, 3> &point, const std::array<double, 3> &normal,
               const PluginInstance &law, const std::string &name) {
  sim.add_plane_wall({point, normal, {0, 0, 0}, plugins.law(law), true, name});
  plane_laws.push_back(&law);
}

// With scene.backend: cuda (or auto on a machine with a GPU), the simulation steps on the GPU: the
// kernels of its pair law, of each plane wall's law (plane_laws, from add_plane) and of the spreader
// with its law.
template <class Real>
void attach_backend(engine::Simulation<Real> &sim, const Scene &scene, const CasePlugins &plugins,
                    const std::vector<const PluginInstance *> &plane_laws) {
#ifdef SPREADMAP_WITH_CUDA
  std::string message;  // said once per run by the simulate stage
  if (cuda::choose_backend(scene.backend, message) != cuda::Backend::cuda) return;
  cuda::ResidentLaws laws;
  laws.pair = cuda::contact_kernels(*plugins.pair.plugin());
  for (const PluginInstance *law : plane_laws) laws.planes.push_back(cuda::contact_kernels(*law->plugin()));
  laws.geometries.push_back(
      {cuda::spreader_kernels(*plugins.spreader.plugin()), cuda::contact_kernels(*plugins.spreader_law.plugin())});
  sim.set_backend(cuda::make_resident_stepper<Real>(sim, std::move(laws)));
#else
  (void)sim, (void)scene, (void)plugins, (void)plane_laws;
#endif
}
}  // namespace

engine::Domain make_domain(const Scene &scene) {
  const Domain &d = scene.domain;
  engine::Domain dom;
  dom.lo = {0, 0, 0};
  dom.hi = {d.length, d.width, d.height};
  dom.periodic = {d.periodic_x, d.periodic_y, false};
  return dom;
}

engine::Settings make_settings(const Scene &scene, double dt) {
  engine::Settings s;
  const TimeSettings &t = scene.time;
  s.dt = dt;
  s.dt_safety = t.safety;
  s.skin = t.skin;
  s.overlap_limit = t.overlap_limit;
  s.sleep = t.sleep;
  s.sleep_speed = t.sleep_speed;
  s.gravity = {0, 0, -scene.gravity};
  s.log = [](const std::string &m) { spdlog::debug("{}", m); };
  return s;
}

template <class Real>
ParticleSet settle_heap(const Scene &scene, PluginRegistry &reg, const std::string &label, const fs::path &scene_file,
                        const std::function<void(double)> &progress) {
  const Powder &powder = scene.powder;
  const auto dom = make_domain(scene);
  CasePlugins plugins(scene, reg, scene_file);
  const double t_settle = powder.settle_time, v_rest = powder.settle_speed;
  // The spreader rests at its start for t < 0: while the heap settles it sees times before that.
  const double rest_shift = -(t_settle + 1.0);

  scene::HeapSpec spec;
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
  // No sphere within a twentieth of the largest diameter of the spreader at rest.
  const double clearance = 0.05 * dmax;
  spec.excluded = [&](double x, double y, double z, double r) {
    const double centre[3] = {x, y, z};
    return plugins.spreader_ops().touches(plugins.spreader.get(), rest_shift, centre, r + clearance) != 0;
  };
  const scene::Heap heap = scene::insert_heap(spec);
  spdlog::info("{}: heap of {} spheres inserted (top {:.2f} mm), settling {:.3g} s", label, heap.size(), heap.top * 1e3,
               t_settle);

  engine::Simulation<Real> sim(dom, plugins.law(plugins.pair), make_settings(scene, scene.time.step));
  ParticleSet set;
  set.x = heap.x;
  set.y = heap.y;
  set.z = heap.z;
  set.radius = heap.r;
  sim.add_particles(set, powder.density);
  std::vector<const PluginInstance *> plane_laws;
  add_plane(sim, plane_laws, plugins, {0, 0, 0}, {0, 0, 1}, plugins.substrate, "substrate");
  add_plane(sim, plane_laws, plugins, {spec.region.lo[0], 0, 0}, {1, 0, 0}, plugins.spreader_law, "heap back wall");
  add_plane(sim, plane_laws, plugins, {spec.region.hi[0], 0, 0}, {-1, 0, 0}, plugins.spreader_law, "heap front wall");
  sim.add_geometry({&plugins.spreader_ops(), plugins.spreader.get(), plugins.law(plugins.spreader_law),
                    plugins.spreader.plugin()->id(), rest_shift});
  attach_backend(sim, scene, plugins, plane_laws);
  const double min_time = 0.3 * t_settle;
  sim.run_until(
      t_settle,
      [&](const engine::Simulation<Real> &s) {
        if (stop_requested()) return false;
        if (progress) progress(s.time() / t_settle);
        if (s.time() < min_time) return true;
        const auto &a = s.arrays();
        Real vmax2 = 0;
        for (std::size_t i = 0; i < s.size(); ++i)
          vmax2 = std::max(vmax2, a.vx[i] * a.vx[i] + a.vy[i] * a.vy[i] + a.vz[i] * a.vz[i]);
        return std::sqrt(double(vmax2)) > v_rest;
      },
      200);
  if (stop_requested())
    throw Interrupted("interrupted while settling the heap of " + label + ": run the same command again to resume");
  auto state = sim.state();
  spdlog::info("{}: heap settled after {:.3g} s ({} steps, {} removed)", label, sim.time(), sim.step_count(),
               sim.removed_count());
  return state;
}

template <class Real>
std::unique_ptr<SpreadingRun<Real>> make_spreading_run(const Scene &scene, PluginRegistry &reg, const ParticleSet &heap,
                                                       const fs::path &scene_file) {
  CasePlugins plugins(scene, reg, scene_file);
  const engine::ContactLaw pair = plugins.law(plugins.pair);
  auto run = std::unique_ptr<SpreadingRun<Real>>(new SpreadingRun<Real>{
      std::move(plugins), engine::Simulation<Real>(make_domain(scene), pair, make_settings(scene, scene.time.step))});
  auto &sim = run->sim;
  const auto &p = run->plugins;
  sim.add_particles(heap, scene.powder.density);
  std::vector<const PluginInstance *> plane_laws;
  add_plane(sim, plane_laws, p, {0, 0, 0}, {0, 0, 1}, p.substrate, "substrate");
  sim.add_geometry({&p.spreader_ops(), p.spreader.get(), p.law(p.spreader_law), p.spreader.plugin()->id()});
  attach_backend(sim, scene, p, plane_laws);
  return run;
}

template <class Real>
bool run_spreading(engine::Simulation<Real> &sim, const CasePlugins &plugins, const Scene &scene, double t_end,
                   const typename engine::Simulation<Real>::StepCallback &callback, std::uint64_t every) {
  const bool sleep = scene.time.sleep;
  const double behind = scene.time.sleep_behind;
  auto follow = [&] {
    if (!sleep) return;
    sim.set_sleep_region(plugins.spreader_pose(sim.time()).x_min - behind);  // behind its trailing edge
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
template struct SpreadingRun<double>;
template struct SpreadingRun<float>;
template std::unique_ptr<SpreadingRun<double>> make_spreading_run<double>(const Scene &, PluginRegistry &,
                                                                          const ParticleSet &, const fs::path &);
template std::unique_ptr<SpreadingRun<float>> make_spreading_run<float>(const Scene &, PluginRegistry &,
                                                                        const ParticleSet &, const fs::path &);
template bool run_spreading<double>(engine::Simulation<double> &, const CasePlugins &, const Scene &, double,
                                    const engine::Simulation<double>::StepCallback &, std::uint64_t);
template bool run_spreading<float>(engine::Simulation<float> &, const CasePlugins &, const Scene &, double,
                                   const engine::Simulation<float>::StepCallback &, std::uint64_t);

}  // namespace spreadmap
