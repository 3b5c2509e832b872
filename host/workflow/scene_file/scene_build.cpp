#include "workflow/scene_file/scene_build.hpp"

#include <spdlog/spdlog.h>
#include <spreadmap/contact.hpp>

#include "core/error.hpp"
#include "workflow/scene_file/scene_parse.hpp"
#include "workflow/scene_file/scene_walls.hpp"
#include "workflow/workflow.hpp"

namespace spreadmap::scene_file {

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

std::unique_ptr<SceneRun> build_scene(const LoadedScene &loaded, PluginRegistry &registry) {
  const SceneFile &s = loaded.scene;
  const LoadedPlugin &law = registry.get("contact", s.law);
  auto run = std::make_unique<SceneRun>();
  const std::string at = s.file.string() + ": ";
  run->pair = PluginInstance(law, s.pair_law.dump(), at + "contact");
  auto bound = [](const PluginInstance &i) { return engine::ContactLaw{i.ops<sm_contact_ops_v1>(), i.get()}; };
  engine::Settings settings;
  settings.dt = s.run.dt;
  settings.dt_safety = s.run.safety;
  settings.overlap_limit = s.run.overlap_limit;
  settings.gravity = s.gravity;
  settings.log = [](const std::string &m) { spdlog::info("{}", m); };
  run->sim = std::make_unique<engine::Simulation<double>>(s.domain, bound(run->pair), settings);
  auto &sim = *run->sim;
  for (const auto &w : s.walls) {
    const PluginInstance &wall_law = run->wall_laws.emplace_back(law, w.law.dump(), at + w.key_path);
    if (w.kind == WallKind::cylinder) {
      const CylinderWall &geometry = run->cylinders.emplace_back(w.cylinder);
      sim.add_geometry({&cylinder_wall_ops(), &geometry, bound(wall_law), w.name, 0.0});
      continue;
    }
    const bool moves_now = w.start <= 0;
    for (const auto &p : planes_of(w)) {
      const std::size_t index =
          sim.add_plane_wall({p.point, p.normal, moves_now ? w.velocity : Vec{0, 0, 0}, bound(wall_law), true, p.name});
      if (!moves_now && w.velocity != Vec{0, 0, 0}) run->delayed.push_back({index, w.velocity, w.start});
    }
  }
  sim.add_particles(loaded.particles.set);
  return run;
}

}  // namespace spreadmap::scene_file
