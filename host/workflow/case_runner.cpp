#include "workflow/case_runner.hpp"

#include <omp.h>
#include <spdlog/spdlog.h>
#include <spreadmap/contact.hpp>
#include <spreadmap/geometry.hpp>

#include <chrono>
#include <cmath>
#include <map>
#include <mutex>

#include "core/error.hpp"
#include "core/files.hpp"
#include "core/stop.hpp"
#include "engine/simulation.hpp"
#include "engine/vtp_io.hpp"
#include "scene/heap.hpp"
#include "scene/coverage.hpp"

namespace spreadmap {
namespace {

using engine::ParticleSet;

constexpr double sphere_volume(double d) { return 3.14159265358979323846 / 6.0 * d * d * d; }

// The bound plugin instances of a case: the contact law three times (particle-particle,
// -substrate, -spreader) and the spreader geometry.
struct Plugins {
  PluginInstance pair, substrate, spreader_law, spreader;
  Plugins(const nlohmann::json &scene, PluginRegistry &reg, const nlohmann::json &spreader_params) {
    const auto &law = reg.get("contact", scene["contact"]["use"].get<std::string>());
    const auto &geo = reg.get("spreader", scene["spreader"]["use"].get<std::string>());
    pair = PluginInstance(law, scene["contact"]["params"].dump(), "scene.contact");
    substrate = PluginInstance(law, scene["substrate"]["law"].dump(), "scene.substrate");
    spreader_law = PluginInstance(law, scene["spreader"]["law"].dump(), "scene.spreader");
    spreader = PluginInstance(geo, spreader_params.dump(), "scene.spreader");
  }
  engine::ContactLaw law(const PluginInstance &i) const { return {i.ops<sm_contact_ops_v1>(), i.get()}; }
};

engine::Domain make_domain(const nlohmann::json &scene) {
  const auto &d = scene["domain"];
  engine::Domain dom;
  dom.lo = {0, 0, 0};
  dom.hi = {d["length"].get<double>(), d["width"].get<double>(), d["height"].get<double>()};
  dom.periodic = {d["periodic_x"].get<bool>(), d["periodic_y"].get<bool>(), false};
  return dom;
}

engine::Settings make_settings(const nlohmann::json &scene, double dt) {
  engine::Settings s;
  const auto &t = scene["time"];
  s.dt = dt;
  s.dt_safety = t["safety"];
  s.skin = t["skin"];
  s.overlap_limit = t["overlap_limit"];
  s.gravity = {0, 0, -scene["gravity"].get<double>()};
  s.log = [](const std::string &m) { spdlog::debug("{}", m); };
  return s;
}

scene::SizeDistribution make_sizes(const nlohmann::json &powder) {
  const std::string kind = powder["distribution"];
  if (kind == "lognormal") return scene::SizeDistribution::lognormal(powder["d50"], powder["sigma"]);
  if (kind == "table") {
    std::vector<double> d, f;
    if (!powder["table"].is_array())
      throw InputError("error: scene.powder.table: a table distribution needs table: [{diameter: 250 um, fraction: 0.5}, ...]");
    for (const auto &row : powder["table"]) {
      d.push_back(row.at("diameter").is_number() ? row.at("diameter").get<double>() : 0.0);
      f.push_back(row.at("fraction").is_number() ? row.at("fraction").get<double>() : 0.0);
    }
    return scene::SizeDistribution::table(d, f);
  }
  return scene::SizeDistribution::monodisperse(powder["diameter"]);
}

// Particles inserted in front of (and under) the spreader and settled under gravity between two
// temporary walls, with the spreader at rest at its start.
template <class Real>
ParticleSet settle_heap(const nlohmann::json &scene, PluginRegistry &reg, const CaseRequest &req) {
  const auto &powder = scene["powder"];
  const auto dom = make_domain(scene);
  nlohmann::json resting = scene["spreader"]["params"];
  resting["travel"] = 0.0;
  resting["end"] = 0.0;
  resting["omega"] = 0.0;
  Plugins plugins(scene, reg, resting);
  sm_pose_v1 pose{};
  plugins.spreader.ops<sm_geometry_ops_v1>()->pose(plugins.spreader.get(), 0.0, &pose);

  scene::HeapSpec spec;
  const auto sizes = make_sizes(powder);
  const double dmax = sizes.upper();
  const double top = powder["heap_top"].get<double>() > 0 ? powder["heap_top"].get<double>() : dom.hi[2] - dmax;
  spec.region = {{powder["heap_from"].get<double>(), dom.lo[1], 0.0}, {powder["heap_to"].get<double>(), dom.hi[1], top}};
  spec.periodic_y = dom.periodic[1];
  spec.sizes = sizes;
  spec.seed = powder["seed"].get<std::uint64_t>();
  if (powder["volume"].get<double>() > 0) spec.solid_volume = powder["volume"];
  else spec.count = powder["count"].get<std::size_t>();
  spec.max_top = dom.hi[2] - 0.5 * dmax;
  if (std::string(pose.shape) == "cylinder")
    spec.excluded_cylinders.push_back({pose.centre[0], pose.centre[2], pose.radius + 0.05 * dmax});
  else
    spec.excluded_boxes.push_back({{pose.centre[0] - 0.5 * pose.thickness - 0.05 * dmax, -1e9, pose.centre[2]},
                                   {pose.centre[0] + 0.5 * pose.thickness + 0.05 * dmax, 1e9, 1e9}});
  const scene::Heap heap = scene::insert_heap(spec);
  spdlog::info("{}: heap of {} spheres inserted (top {:.2f} mm), settling {:.3g} s", req.id, heap.size(), heap.top * 1e3,
               powder["settle_time"].get<double>());

  engine::Simulation<Real> sim(dom, plugins.law(plugins.pair), make_settings(scene, scene["time"]["step"]));
  ParticleSet set;
  set.x = heap.x; set.y = heap.y; set.z = heap.z;
  set.radius = heap.r;
  sim.add_particles(set, powder["density"]);
  sim.add_plane_wall({{0, 0, 0}, {0, 0, 1}, {0, 0, 0}, plugins.law(plugins.substrate), true, "substrate"});
  sim.add_plane_wall({{spec.region.lo[0], 0, 0}, {1, 0, 0}, {0, 0, 0}, plugins.law(plugins.spreader_law), true, "heap back wall"});
  sim.add_plane_wall({{spec.region.hi[0], 0, 0}, {-1, 0, 0}, {0, 0, 0}, plugins.law(plugins.spreader_law), true, "heap front wall"});
  sim.add_geometry({plugins.spreader.ops<sm_geometry_ops_v1>(), plugins.spreader.get(), plugins.law(plugins.spreader_law),
                    "spreader/" + scene["spreader"]["use"].get<std::string>()});
  const double t_settle = powder["settle_time"], v_rest = powder["settle_speed"];
  const double min_time = 0.3 * t_settle;
  sim.run_until(t_settle, [&](const engine::Simulation<Real> &s) {
    if (stop_requested()) return false;
    if (req.progress) req.progress(0.1 * s.time() / t_settle, "settling");
    if (s.time() < min_time) return true;
    const auto &a = s.arrays();
    Real vmax2 = 0;
    for (std::size_t i = 0; i < s.size(); ++i) vmax2 = std::max(vmax2, a.vx[i] * a.vx[i] + a.vy[i] * a.vy[i] + a.vz[i] * a.vz[i]);
    return std::sqrt(double(vmax2)) > v_rest;
  }, 200);
  if (stop_requested()) throw Interrupted("interrupted while settling the heap of " + req.id + ": run the same command again to resume");
  auto state = sim.state();
  spdlog::info("{}: heap settled after {:.3g} s ({} steps, {} removed)", req.id, sim.time(), sim.step_count(), sim.removed_count());
  return state;
}

std::mutex heap_mutex;
std::map<std::string, std::shared_ptr<std::mutex>> heap_locks;

template <class Real>
ParticleSet settled_heap(const nlohmann::json &scene, PluginRegistry &reg, const CaseRequest &req) {
  const std::string key = heap_hash(scene);
  std::shared_ptr<std::mutex> lock;
  {
    std::lock_guard<std::mutex> g(heap_mutex);
    auto &l = heap_locks[key];
    if (!l) l = std::make_shared<std::mutex>();
    lock = l;
  }
  std::lock_guard<std::mutex> g(*lock);  // one case settles; the others wait and reuse it
  const fs::path file = req.heaps / ("heap_" + key + ".vtp");
  if (fs::exists(file)) {
    spdlog::debug("{}: reusing settled heap {}", req.id, file.string());
    return engine::read_vtp(file).particles;
  }
  ParticleSet heap = settle_heap<Real>(scene, reg, req);
  engine::write_vtp(file, heap, 0.0);
  return heap;
}

template <class Real> nlohmann::json spread(const CaseRequest &req, PluginRegistry &reg) {
  const auto &scene = req.scene;
  ParticleSet heap = settled_heap<Real>(scene, reg, req);
  const auto dom = make_domain(scene);
  Plugins plugins(scene, reg, scene["spreader"]["params"]);
  const auto *gops = plugins.spreader.ops<sm_geometry_ops_v1>();
  engine::Simulation<Real> sim(dom, plugins.law(plugins.pair), make_settings(scene, scene["time"]["step"]));
  sim.add_particles(heap, scene["powder"]["density"]);
  sim.add_plane_wall({{0, 0, 0}, {0, 0, 1}, {0, 0, 0}, plugins.law(plugins.substrate), true, "substrate"});
  sim.add_geometry({gops, plugins.spreader.get(), plugins.law(plugins.spreader_law),
                    "spreader/" + scene["spreader"]["use"].get<std::string>()});

  const fs::path checkpoint = req.dir / "checkpoint.bin";
  const std::string hash = case_hash(scene);
  const fs::path checkpoint_hash = req.dir / "checkpoint.hash";
  if (fs::exists(checkpoint) && fs::exists(checkpoint_hash) && read_text(checkpoint_hash) == hash) {
    sim.load_checkpoint(checkpoint);
    spdlog::info("{}: resuming from its checkpoint at t = {:.4g} s", req.id, sim.time());
  }
  const double duration = gops->duration(plugins.spreader.get()) + scene["time"]["relax"].get<double>();
  const double interval = scene["time"]["checkpoint_interval"];
  const int snapshots = scene["time"]["snapshots"];
  auto last_checkpoint = std::chrono::steady_clock::now();
  const auto t0 = last_checkpoint;
  const double steps_before = double(sim.step_count());
  auto save_checkpoint = [&] {
    write_atomic(checkpoint_hash, hash);
    sim.save_checkpoint(checkpoint);
  };
  std::vector<engine::SeriesEntry> series;
  int next_snapshot = 1;
  // one snapshot time per interval; callbacks every 100 steps are cheap against the step cost
  bool ok = sim.run_until(duration, [&](const engine::Simulation<Real> &s) {
    const auto now = std::chrono::steady_clock::now();
    if (req.progress) req.progress(0.1 + 0.9 * s.time() / duration, "");
    if (snapshots > 0 && s.time() >= duration * next_snapshot / (snapshots + 1)) {
      const std::string name = "series/state_" + std::to_string(next_snapshot) + ".vtp";
      engine::write_vtp(req.dir / name, s.state(), s.time());
      series.push_back({s.time(), name});
      ++next_snapshot;
    }
    if (stop_requested()) return false;
    if (std::chrono::duration<double>(now - last_checkpoint).count() > interval) {
      save_checkpoint();
      last_checkpoint = now;
    }
    return true;
  }, 100);
  if (!ok) {
    save_checkpoint();
    throw Interrupted("interrupted: " + req.id + " saved its checkpoint at t = " + fmt::format("{:.4g}", sim.time()) +
                      " s; run the same command again to resume");
  }
  const ParticleSet state = sim.state();
  engine::write_vtp(req.dir / "state.vtp", state, sim.time());
  if (!series.empty()) {
    series.push_back({sim.time(), "state.vtp"});
    engine::write_pvd(req.dir / "series.pvd", series);
  }
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const auto &c = sim.counters();
  sm_pose_v1 pose{};
  gops->pose(plugins.spreader.get(), sim.time(), &pose);
  nlohmann::json out = {
      {"id", req.id}, {"hash", hash}, {"status", "done"}, {"inputs", req.inputs},
      {"particles_start", heap.size()}, {"particles_end", state.size()}, {"removed", sim.removed_count()},
      {"steps", sim.step_count()}, {"dt", sim.dt()}, {"dt_critical", sim.critical_dt()},
      {"simulated_time", sim.time()}, {"wall_seconds_last_run", wall},
      {"particle_steps_per_second", c.particle_steps_per_second()}, {"list_builds", c.list_builds},
      {"steps_this_run", double(sim.step_count()) - steps_before}, {"rotation_integrated", sim.rotation_integrated()},
      {"precision", scene["precision"]},
      {"spreader_end", {{"x", pose.centre[0]}, {"z", pose.centre[2]}, {"radius", pose.radius}}},
  };
  write_atomic(req.dir / "case.json", out.dump(2) + "\n");
  std::error_code ec;
  fs::remove(checkpoint, ec);
  fs::remove(checkpoint_hash, ec);
  return out;
}

}  // namespace

std::string case_hash(const nlohmann::json &scene) {
  nlohmann::json s = scene;
  s["time"].erase("checkpoint_interval");
  s.erase("threads");
  s.erase("backend");
  return stable_hash(s.dump());
}

std::string heap_hash(const nlohmann::json &scene) {
  nlohmann::json s = {{"powder", scene["powder"]}, {"domain", scene["domain"]}, {"contact", scene["contact"]},
                      {"substrate", scene["substrate"]}, {"spreader", scene["spreader"]}, {"gravity", scene["gravity"]},
                      {"precision", scene["precision"]}, {"time", scene["time"]}};
  for (const char *k : {"U", "omega", "travel", "end"}) s["spreader"]["params"].erase(k);
  for (const char *k : {"relax", "checkpoint_interval", "snapshots"}) s["time"].erase(k);
  return stable_hash(s.dump());
}

bool case_finished(const fs::path &dir, const std::string &hash) {
  std::error_code ec;
  if (!fs::exists(dir / "case.json", ec) || !fs::exists(dir / "state.vtp", ec)) return false;
  try {
    const auto j = nlohmann::json::parse(read_text(dir / "case.json"));
    return j.value("hash", "") == hash && j.value("status", "") == "done";
  } catch (...) {
    return false;
  }
}

nlohmann::json run_case(const CaseRequest &request, PluginRegistry &registry) {
  fs::create_directories(request.dir);
  fs::create_directories(request.heaps);
  if (request.threads > 0) omp_set_num_threads(request.threads);
  if (request.scene["precision"] == "float") return spread<float>(request, registry);
  return spread<double>(request, registry);
}

}  // namespace spreadmap
