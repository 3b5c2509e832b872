// spreadmap simulate SCENE.yaml [--out DIR]: one explicit scene (docs/scenes.md), run from its
// particles and walls to its duration, with the outputs of scene_outputs.hpp at the chosen times.
#ifdef _OPENMP
#include <omp.h>
#endif
#include <fmt/format.h>
#include <spdlog/spdlog.h>
#include <spreadmap/contact.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "core/files.hpp"
#include "core/stop.hpp"
#include "engine/plugin_law.hpp"
#include "workflow/stage/command_line.hpp"
#include "workflow/stage/commands.hpp"
#include "workflow/scene/scene_build.hpp"
#include "workflow/scene/scene_outputs.hpp"
#include "workflow/scene/scene_run.hpp"

namespace spreadmap {

namespace {

nlohmann::json vec(const scene::Vec &v) { return {v[0], v[1], v[2]}; }

// The scene as it runs, SI, for scene.json beside the outputs.
nlohmann::json resolved(const scene::SceneFile &s, std::size_t particles) {
  using scene::WallKind;
  nlohmann::json walls = nlohmann::json::array();
  for (const auto &w : s.walls) {
    nlohmann::json j = {{"name", w.name}, {"law", w.law}, {"velocity", vec(w.velocity)}, {"start", w.start}};
    if (std::isfinite(w.stop)) j["stop"] = w.stop;
    if (w.kind == WallKind::plane) {
      j["type"] = "plane";
      j["point"] = vec(w.point);
      j["normal"] = vec(w.normal);
    } else if (w.kind == WallKind::box) {
      j["type"] = "box";
      j["lo"] = vec(w.lo);
      j["hi"] = vec(w.hi);
      j["open_top"] = w.open_top;
    } else if (w.kind == WallKind::block) {
      j["type"] = "block";
      j["lo"] = vec(w.lo);
      j["hi"] = vec(w.hi);
    } else if (w.kind == WallKind::spreader) {
      j["type"] = "spreader";
      j["spreader"] = {{"use", w.spreader.use}, {"params", w.spreader.params}};
    } else {
      const auto &c = w.cylinder;
      j["type"] = "cylinder";
      j["base"] = {c.base[0], c.base[1], c.base[2]};
      j["axis"] = {c.axis[0], c.axis[1], c.axis[2]};
      j["radius"] = c.radius;
      j["height"] = c.height;
      j["inside"] = c.inside;
      j["omega"] = c.omega;
    }
    walls.push_back(j);
  }
  return {{"name", s.name},
          {"domain",
           {{"lo", vec(s.domain.lo)},
            {"hi", vec(s.domain.hi)},
            {"periodic", {s.domain.periodic[0], s.domain.periodic[1], s.domain.periodic[2]}}}},
          {"gravity", vec(s.gravity)},
          {"contact", {{"use", s.law}, {"params", s.pair_law}}},
          {"walls", walls},
          {"particles", particles},
          {"run",
           {{"duration", s.run.duration},
            {"dt", s.run.dt},
            {"safety", s.run.safety},
            {"output_times", s.run.output_times}}}};
}

}  // namespace

int cmd_simulate(int argc, char **argv) {
  namespace po = boost::program_options;
  po::options_description d("simulate options");
  std::string file, out;
  cli::Common c;
  d.add_options()("scene", po::value(&file)->required(), "scene file (docs/scenes.md)")(
      "out", po::value(&out), "output folder (default runs/<scene name>)");
  c.add(d);
  po::positional_options_description p;
  p.add("scene", 1);
  po::variables_map vm;
  if (!cli::parse(argc, argv, d, p, vm, "simulate SCENE.yaml [--out DIR]")) return 0;
  c.apply();
  auto &registry = PluginRegistry::global();
  const scene::LoadedScene loaded = scene::load_scene(file, registry);
  const scene::SceneFile &spec = loaded.scene;
  const fs::path dir = out.empty() ? fs::path("runs") / spec.name : fs::path(out);
#ifdef _OPENMP
  if (spec.run.threads > 0) omp_set_num_threads(static_cast<int>(spec.run.threads));
#endif
  auto run = scene::build_scene<double>(loaded, registry);
  auto &sim = *run->sim;
  const engine::ContactLaw pair_law = engine::bound_law(run->pair);
  write_atomic(dir / "scene.json", resolved(spec, sim.size()).dump(2) + "\n");
  spdlog::info("{}: {} particles, {} walls, {:g} s in {} outputs to {}", spec.name, sim.size(), spec.walls.size(),
               spec.run.duration, spec.run.output_times.size(), dir.string());

  scene::SceneOutputs outputs(dir, spec.run.particles_csv, spec.run.contacts_csv);
  const auto t0 = std::chrono::steady_clock::now();
  auto keep_going = [](const engine::Simulation<double> &) { return !stop_requested(); };
  for (const double t : spec.run.output_times) {
    if (!scene::advance_scene(*run, t, keep_going))
      throw Interrupted(
          fmt::format("interrupted at t = {:.4g} s; the outputs so far are in {}", sim.time(), dir.string()));
    outputs.write(sim, pair_law);
    spdlog::debug("{}: output {} at t = {:.6g} s", spec.name, outputs.count() - 1, sim.time());
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const nlohmann::json summary = {{"time", sim.time()},
                                  {"steps", sim.step_count()},
                                  {"dt", sim.dt()},
                                  {"critical_dt", sim.critical_dt()},
                                  {"particles", sim.size()},
                                  {"fixed", sim.fixed_count()},
                                  {"removed", sim.removed_count()},
                                  {"outputs", outputs.count()},
                                  {"wall_seconds", seconds}};
  write_atomic(dir / "summary.json", summary.dump(2) + "\n");
  spdlog::info("{}: {} steps (dt = {:.4g} s) in {:.1f} s; {} outputs, states.pvd opens them in ParaView", spec.name,
               sim.step_count(), sim.dt(), seconds, outputs.count());
  return 0;
}

}  // namespace spreadmap
