// bench_scene_switches: what "model only what a scene requires" saves, and what it costs in accuracy.
// The quickstart's scene (quick preset: 1600 spheres, roller at U = 100 mm/s, omega = 0) is spread
// from the same settled heaps in these variants, each timed over the whole spreading run (one thread
// count, interleaved over the heaps):
//   reference          the scene as the quick preset has it
//   + 2 idle walls     two plane walls no particle can touch (1 mm outside the domain's top and back): the price of
//                      walls that are present; a scene without them has no wall loop at all
//   frictionless       mu = 0 and no rolling resistance everywhere: no law makes torque, so rotation
//                      is not integrated (as the engine decides)
//   frictionless, rotation forced    the same scene with rotation integrated anyway
//   long strip         the same strip with 80 mm of travel and 4000 spheres (most end in the layer)
//   long strip, sleep  time.sleep: particles at rest far behind the roller stop being integrated
//                      (the default rest speed 1 mm/s and distance 5 mm, and a looser 5 mm/s, 2 mm)
// Printed per variant: wall time (median over heaps), its saving against its own baseline, V_s and
// R_q over the quickstart's sampling region (mean and sample standard deviation over the heaps), and
// their change against the baseline in units of the combined standard error. Rotation skipping must
// leave the end state bitwise unchanged (no torque: every spin stays exactly zero); the others must
// stay inside the heap-to-heap scatter.
//
// Usage: bench_scene_switches [--heaps 3] [--threads 1]
#include <omp.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include "analysis/summary.hpp"
#include "core/registry.hpp"
#include "core/schema.hpp"
#include "engine/plugin_law.hpp"
#include "workflow/stage_table.hpp"
#include "workflow/spreading/case_setup.hpp"
#include "workflow/characterise/layer_eval.hpp"
#include "workflow/spreading/scene_section.hpp"
#include "workflow/file/workflow.hpp"

namespace sm = spreadmap;
namespace fs = std::filesystem;

namespace {

struct Variant {
  std::string name;
  std::string baseline;     // the variant its saving and error are measured against
  bool long_strip = false;  // the long strip instead of the quickstart's scene
  bool sleep = false, idle_walls = false, frictionless = false, force_rotation = false;
  double sleep_speed = 1e-3, sleep_behind = 5e-3;  // [m/s], [m]
};

// The quickstart's strip stretched to 80 mm of travel with a heap to match (4000 spheres): most of
// the powder ends in the layer behind the roller, as in the study's 100 mm plate, which is where
// sleeping can save anything.
sm::Scene long_strip(sm::Scene scene) {
  scene.domain.length = 0.1;
  scene.powder.count = 4000;
  scene.powder.heap_to = 0.024;
  scene.spreader.params["travel"] = 0.08;
  return scene;
}

struct Outcome {
  double wall = 0, vs = 0, rq = 0;
  std::size_t asleep_at_end = 0;
  double awake_fraction = 1;  // integrated particle-steps / particle-steps
  std::vector<double> end_state;
};

std::string cpu_model() {
  std::ifstream in("/proc/cpuinfo");
  for (std::string line; std::getline(in, line);)
    if (line.rfind("model name", 0) == 0) return line.substr(line.find(':') + 2);
  return "unknown";
}

using Stats = sm::analysis::MeanSd;
const auto stats = sm::analysis::mean_sd;
double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

sm::Scene variant_scene(sm::Scene scene, const Variant &v) {
  if (v.sleep) {
    scene.time.sleep = true;
    scene.time.sleep_speed = v.sleep_speed;
    scene.time.sleep_behind = v.sleep_behind;
  }
  if (v.frictionless)
    for (nlohmann::json *law : {&scene.contact.params, &scene.substrate.law, &scene.spreader.law}) {
      (*law)["friction"] = 0.0;
      if (law->contains("rolling_friction")) (*law)["rolling_friction"] = 0.0;
    }
  return scene;
}

Outcome spread(const sm::Scene &scene, sm::PluginRegistry &registry, const sm::engine::ParticleSet &heap,
               const Variant &v, const fs::path &scene_file) {
  auto run = sm::make_spreading_run<double>(scene, registry, heap, scene_file);
  auto &sim = run->sim;
  if (v.force_rotation) sim.force_rotation(true);
  if (v.idle_walls) {
    const sm::PluginInstance &substrate = run->built->wall_laws.front();  // the substrate's law
    const sm::engine::ContactLaw law = sm::engine::bound_law(substrate);
    // 1 mm outside the domain's top and back faces: nothing inside can reach them
    const double h = scene.domain.height;
    sim.add_plane_wall({{0, 0, h + 1e-3}, {0, 0, -1}, {0, 0, 0}, law, true, "ceiling"});
    sim.add_plane_wall({{-1e-3, 0, 0}, {1, 0, 0}, {0, 0, 0}, law, true, "back wall"});
  }
  const auto spreader = run->spreader.description();
  const double duration = spreader.duration + scene.time.relax;
  const auto t0 = std::chrono::steady_clock::now();
  sm::run_spreading(sim, run->spreader, scene, duration);
  Outcome o;
  o.wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const auto &c = sim.counters();
  o.awake_fraction = c.particle_steps > 0 ? c.integrated_particle_steps / c.particle_steps : 1;
  o.asleep_at_end = sim.sleeping_count();
  const sm::engine::ParticleSet s = sim.state();
  sm::LayerRequest rq;
  rq.region = sm::default_region(scene, spreader);
  rq.periodic_y = std::make_pair(0.0, scene.domain.width);
  sm::take_spreader(rq, spreader);
  {
    sm::Diagnostics diag;  // the layer plugin's defaults (cell d/5), as the characterise stage uses them
    rq.params = sm::validate_params(sm::SchemaView::of(*registry.get("metrics", "layer").descriptor), YAML::Node(),
                                    "<defaults>", "layer", diag);
    diag.throw_if_any();
  }
  const auto layer = sm::characterise_layer(registry, rq, s);
  o.vs = layer.metrics["vs"];
  o.rq = layer.metrics["rq"];
  std::vector<std::size_t> order(s.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return s.id[a] < s.id[b]; });
  for (std::size_t i : order)
    for (const auto *col : {&s.x, &s.y, &s.z, &s.vx, &s.vy, &s.vz, &s.wx, &s.wy, &s.wz})
      o.end_state.push_back((*col)[i]);
  return o;
}

}  // namespace

int main(int argc, char **argv) {
  int heaps = 3, threads = 1;
  for (int k = 1; k + 1 < argc; k += 2) {
    const std::string a = argv[k];
    if (a == "--heaps") heaps = std::max(2, std::atoi(argv[k + 1]));
    else if (a == "--threads") threads = std::max(1, std::atoi(argv[k + 1]));
    else {
      std::fprintf(stderr, "usage: bench_scene_switches [--heaps 3] [--threads 1]\n");
      return 2;
    }
  }
  spdlog::set_level(spdlog::level::warn);
  sm::PluginRegistry registry(sm::PluginRegistry::default_roots());
  const fs::path workflow = fs::path(SPREADMAP_SOURCE_DIR) / "workflows" / "quickstart.yaml";
  sm::Diagnostics diag;
  const auto resolved = sm::resolve_scene(sm::load_workflow(workflow, sm::stage_names()), registry, diag);
  diag.throw_if_any();
  sm::Scene scene = *resolved;
  scene.spreader.params["U"] = 0.1;
  scene.spreader.params["omega"] = 0.0;

  const std::vector<Variant> variants = {
      {"reference", "reference"},
      {"+ 2 idle walls", "reference", false, false, true},
      {"frictionless, rotation forced", "frictionless, rotation forced", false, false, false, true, true},
      {"frictionless (rotation skipped)", "frictionless, rotation forced", false, false, false, true, false},
      {"long strip", "long strip", true},
      {"long strip, sleep", "long strip", true, true},
      {"long strip, sleep 5 mm/s 2 mm", "long strip", true, true, false, false, false, 5e-3, 2e-3},
  };
  std::printf("bench_scene_switches: %s at U = 100 mm/s, omega = 0; %d heaps, %d thread%s\n",
              workflow.filename().c_str(), heaps, threads, threads > 1 ? "s" : "");
  std::printf("machine: %s, %u hardware threads\n", cpu_model().c_str(), std::thread::hardware_concurrency());
  std::fflush(stdout);

  std::vector<std::vector<Outcome>> out(variants.size());
  for (int h = 1; h <= heaps; ++h) {
    scene.powder.seed = h;
    omp_set_num_threads(std::min(2, omp_get_num_procs()));
    const auto heap = sm::settle_heap<double>(scene, registry, "bench", workflow);
    const auto long_heap = sm::settle_heap<double>(long_strip(scene), registry, "bench", workflow);
    omp_set_num_threads(threads);
    for (std::size_t v = 0; v < variants.size(); ++v) {
      const Variant &var = variants[v];
      out[v].push_back(spread(variant_scene(var.long_strip ? long_strip(scene) : scene, var), registry,
                              var.long_strip ? long_heap : heap, var, workflow));
      const Outcome &o = out[v].back();
      std::printf(
          "  heap %d, %-32s %6.2f s  V_s %.4f mm^2/s  R_q %.2f um  integrated %.1f %% of particle-steps, %zu "
          "asleep at the end\n",
          h, variants[v].name.c_str(), o.wall, o.vs * 1e6, o.rq * 1e6, 100 * o.awake_fraction, o.asleep_at_end);
      std::fflush(stdout);
    }
  }

  std::printf("\n%-32s %9s %8s %20s %20s %10s %10s %9s\n", "variant", "wall [s]", "saving", "V_s [mm^2/s]", "R_q [um]",
              "dV_s [σ]", "dR_q [σ]", "bitwise");
  for (std::size_t v = 0; v < variants.size(); ++v) {
    std::size_t b = 0;
    while (variants[b].name != variants[v].baseline) ++b;
    std::vector<double> wall, vs, rq, wall_b, vs_b, rq_b;
    bool same = true;
    for (int h = 0; h < heaps; ++h) {
      wall.push_back(out[v][h].wall), vs.push_back(out[v][h].vs), rq.push_back(out[v][h].rq);
      wall_b.push_back(out[b][h].wall), vs_b.push_back(out[b][h].vs), rq_b.push_back(out[b][h].rq);
      same = same && out[v][h].end_state.size() == out[b][h].end_state.size() &&
             std::memcmp(out[v][h].end_state.data(), out[b][h].end_state.data(),
                         out[v][h].end_state.size() * sizeof(double)) == 0;
    }
    const Stats s_vs = stats(vs), s_rq = stats(rq), b_vs = stats(vs_b), b_rq = stats(rq_b);
    const double n = heaps;
    auto in_sigma = [&](const Stats &a, const Stats &r) {
      const double se = std::sqrt((a.sd * a.sd + r.sd * r.sd) / n);
      return se > 0 ? (a.mean - r.mean) / se : 0.0;
    };
    std::printf("%-32s %9.2f %7.1f%% %11.4f ± %6.4f %11.2f ± %6.2f %+10.2f %+10.2f %9s\n", variants[v].name.c_str(),
                median(wall), v == b ? 0.0 : 100 * (1 - median(wall) / median(wall_b)), s_vs.mean * 1e6, s_vs.sd * 1e6,
                s_rq.mean * 1e6, s_rq.sd * 1e6, v == b ? 0.0 : in_sigma(s_vs, b_vs),
                v == b ? 0.0 : in_sigma(s_rq, b_rq),
                v == b ? "-"
                : same ? "yes"
                       : "no");
  }
  std::printf(
      "\nsaving and changes are against the variant's baseline (reference, or the frictionless scene with "
      "rotation forced); σ: combined standard error of the two means over %d heaps\n",
      heaps);
  return 0;
}
