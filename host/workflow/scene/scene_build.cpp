#include "workflow/scene/scene_build.hpp"

#ifdef SPREADMAP_WITH_CUDA
#include "cuda/backend.hpp"
#include "cuda/resident_stepper.hpp"
#endif

#include <fmt/format.h>
#include <spdlog/spdlog.h>
#include <spreadmap/contact.hpp>

#include <cmath>
#include <yaml-cpp/yaml.h>

#include "core/error.hpp"
#include "core/plugin_abi.hpp"
#include "engine/plugin_law.hpp"
#include "workflow/scene/scene_parse.hpp"
#include "workflow/scene/scene_walls.hpp"
#include "workflow/scene/spreader_span.hpp"
#include "workflow/file/workflow.hpp"

namespace spreadmap::scene {
namespace {

engine::Settings settings_of(const SceneFile &s) {
  engine::Settings settings;
  settings.dt = s.run.dt;
  settings.dt_safety = s.run.safety;
  settings.skin = s.run.skin;
  settings.overlap_limit = s.run.overlap_limit;
  settings.sleep = s.run.sleep;
  settings.sleep_speed = s.run.sleep_speed;
  settings.gravity = s.gravity;
  if (s.run.log_engine) settings.log = [](const std::string &m) { spdlog::info("{}", m); };
  else settings.log = [](const std::string &m) { spdlog::debug("{}", m); };
  return settings;
}

// With backend cuda (or auto on a machine with a GPU) the simulation steps on the GPU: the kernels
// of its pair law, of each plane's law (in the order the planes were added) and of each spreader
// with its law. Cylinders and CPU-only spreaders (a mesh) have no GPU kernels, and fixed particles and
// attraction across a gap step on the CPU only: such a scene steps on the CPU (backend auto).
template <class Real>
void attach_backend(engine::Simulation<Real> &sim, const SceneFile &s, const SceneRun<Real> &run,
                    const std::vector<const PluginInstance *> &plane_laws,
                    const std::vector<const PluginInstance *> &spreader_laws) {
#ifdef SPREADMAP_WITH_CUDA
  std::string message;  // said once per run by the caller
  if (s.backend == "cpu" || cuda::choose_backend(s.backend, message) != cuda::Backend::cuda) return;
  if (!run.cylinders.empty() || !run.blocks.empty()) {
    spdlog::warn("{}: cylinder and block walls step on the CPU only; the scene runs on the CPU", s.file.string());
    return;
  }
  for (const auto &spreader : run.spreaders)
    if (!(spreader.instance->plugin()->descriptor->backends & SM_BACKEND_CUDA) && s.backend == "auto") {
      spdlog::info("{}: spreader/{} steps on the CPU only; the scene runs on the CPU", s.file.string(),
                   spreader.instance->plugin()->descriptor->name);
      return;  // an explicit cuda is refused by spreader_kernels, naming the plugin
    }
  if (sim.fixed_count() > 0 && s.backend == "auto") {  // an explicit cuda is refused by set_backend
    spdlog::info("{}: fixed particles step on the CPU only; the scene runs on the CPU", s.file.string());
    return;
  }
  if (sim.attracts_across_gap() && s.backend == "auto") {
    spdlog::info("{}: van der Waals attraction across a gap steps on the CPU only; the scene runs on the CPU",
                 s.file.string());
    return;
  }
  // The CUDA kernels keep a law's own history; a rolling spring (rolling_model epsd) adds to it.
  auto without_spring = [](const PluginInstance &law) {
    return engine::law_history(engine::bound_law(law)) == cuda::contact_kernels(*law.plugin()).ops->history;
  };
  bool kernels_fit = without_spring(run.pair);
  for (const PluginInstance *law : plane_laws) kernels_fit = kernels_fit && without_spring(*law);
  for (const PluginInstance *law : spreader_laws) kernels_fit = kernels_fit && without_spring(*law);
  if (!kernels_fit) {
    if (s.backend == "auto") {
      spdlog::info("{}: the rolling spring (rolling_model: epsd) steps on the CPU only; the scene runs on the CPU",
                   s.file.string());
      return;
    }
    throw InputError(fmt::format("{}: scene.backend: cuda: the rolling spring (rolling_model: epsd) steps on "
                                 "the CPU only: set scene.backend: cpu or auto, or rolling_model: constant",
                                 s.file.string()));
  }
  cuda::ResidentLaws laws;
  laws.pair = cuda::contact_kernels(*run.pair.plugin());
  for (const PluginInstance *law : plane_laws) laws.planes.push_back(cuda::contact_kernels(*law->plugin()));
  for (std::size_t k = 0; k < run.spreaders.size(); ++k)
    laws.geometries.push_back({cuda::spreader_kernels(*run.spreaders[k].instance->plugin()),
                               cuda::contact_kernels(*spreader_laws[k]->plugin())});
  sim.set_backend(cuda::make_resident_stepper<Real>(sim, std::move(laws)));
#else
  (void)sim, (void)s, (void)run, (void)plane_laws, (void)spreader_laws;
#endif
}

}  // namespace

sm_spreader_description_v2 BoundSpreader::description() const {
  sm_spreader_description_v2 d{};
  ops().describe(instance->get(), &d);
  return d;
}

sm_spreader_pose_v2 BoundSpreader::pose(double t) const {
  sm_spreader_pose_v2 p{};
  ops().pose(instance->get(), t + time_offset, &p);
  return p;
}

LoadedScene load_scene(const fs::path &file, PluginRegistry &registry) {
  const YAML::Node root = load_yaml(file);
  Diagnostics diag;
  auto scene = parse_scene(file, root, registry, diag);
  diag.throw_if_any();
  LoadedScene out{std::move(*scene), {}};
  out.particles = load_particles(out.scene);
  check_particles(out.scene, out.particles);
  return out;
}

template <class Real> std::unique_ptr<SceneRun<Real>> build_scene(const LoadedScene &loaded, PluginRegistry &registry) {
  const SceneFile &s = loaded.scene;
  const LoadedPlugin &law = registry.get("contact", s.law);
  auto run = std::make_unique<SceneRun<Real>>();
  const std::string at = s.file.string() + ": ";
  run->pair = PluginInstance(law, s.pair_law.dump(), at + "contact");
  run->sim = std::make_unique<engine::Simulation<Real>>(s.domain, engine::bound_law(run->pair), settings_of(s));
  auto &sim = *run->sim;
  sim.add_particles(loaded.particles.set, s.particles.density);
  std::vector<const PluginInstance *> plane_laws, spreader_laws;
  for (const auto &w : s.walls) {
    const PluginInstance &wall_law = run->wall_laws.emplace_back(law, w.law.dump(), at + w.key_path);
    if (w.kind == WallKind::cylinder) {
      const CylinderWall &geometry = run->cylinders.emplace_back(w.cylinder);
      sim.add_geometry({&cylinder_wall_ops(), &geometry, engine::bound_law(wall_law), w.name, 0.0});
      continue;
    }
    if (w.kind == WallKind::block) {
      const BlockWall &geometry = run->blocks.emplace_back(block_of(w));
      sim.add_geometry({&block_wall_ops(), &geometry, engine::bound_law(wall_law), w.name, 0.0});
      continue;
    }
    if (w.kind == WallKind::spreader) {
      const PluginInstance &plugin = run->spreader_plugins.emplace_back(registry.get("spreader", w.spreader.use),
                                                                        w.spreader.params.dump(), at + w.key_path);
      const BoundSpreader spreader{&plugin, w.spreader.time_offset};
      if (const auto shortfall = spreader_span_shortfall(spreader.description(), s.domain);
          shortfall && shortfall->periodic)
        throw InputError(fmt::format("{}{}: {}\n  {}", at, w.key_path, shortfall->what, shortfall->fix));
      sim.add_geometry({&spreader.ops(), plugin.get(), engine::bound_law(wall_law), w.name, w.spreader.time_offset,
                        abi_minor(*plugin.plugin()->descriptor)});
      run->spreaders.push_back(spreader);
      spreader_laws.push_back(&wall_law);
      continue;
    }
    const bool moves_now = w.start <= 0;
    const Vec velocity_now = moves_now ? w.velocity : Vec{0, 0, 0};
    for (const auto &p : planes_of(w)) {
      const std::size_t index =
          sim.add_plane_wall({p.point, p.normal, velocity_now, engine::bound_law(wall_law), true, p.name});
      plane_laws.push_back(&wall_law);
      if (w.velocity == Vec{0, 0, 0}) continue;
      if (!moves_now) run->delayed.push_back({index, w.velocity, w.start});
      if (std::isfinite(w.stop)) run->delayed.push_back({index, Vec{0, 0, 0}, w.stop});
    }
  }
  attach_backend(sim, s, *run, plane_laws, spreader_laws);
  return run;
}

template std::unique_ptr<SceneRun<double>> build_scene<double>(const LoadedScene &, PluginRegistry &);
template std::unique_ptr<SceneRun<float>> build_scene<float>(const LoadedScene &, PluginRegistry &);

}  // namespace spreadmap::scene
