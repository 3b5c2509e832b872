#include "workflow/simulate/case_runner.hpp"

#include <omp.h>
#include <spdlog/spdlog.h>
#include <spreadmap/contact.hpp>
#include <spreadmap/geometry.hpp>

#include <chrono>
#include <cmath>
#include <map>
#include <mutex>

#include "core/error.hpp"
#include "engine/errors.hpp"
#include "workflow/simulate/coarse_grain.hpp"
#include "core/files.hpp"
#include "core/stop.hpp"
#include "engine/simulation.hpp"
#include "engine/vtp_io.hpp"
#include "scene/coverage.hpp"
#include "workflow/simulate/case_setup.hpp"

namespace spreadmap {
namespace {

using engine::ParticleSet;

constexpr double sphere_volume(double d) { return 3.14159265358979323846 / 6.0 * d * d * d; }

std::mutex heap_mutex;
std::map<std::string, std::shared_ptr<std::mutex>> heap_locks;

template <class Real> ParticleSet settled_heap(const Scene &scene, PluginRegistry &reg, const CaseRequest &req) {
  const std::string key = heap_hash(scene, reg);
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
  ParticleSet heap = settle_heap<Real>(scene, reg, req.id, req.dir / "scene.json", [&req](double f) {
    if (req.progress) req.progress(0.1 * f, "settling");
  });
  engine::write_vtp(file, heap, 0.0);
  return heap;
}

template <class Real> nlohmann::json spread(const CaseRequest &req, PluginRegistry &reg) {
  const auto &scene = req.scene;
  ParticleSet heap = settled_heap<Real>(scene, reg, req);
  const auto run = make_spreading_run<Real>(scene, reg, heap, req.dir / "scene.json");
  auto &sim = run->sim;
  const auto &spreader_plugin = run->spreader;

  const fs::path checkpoint = req.dir / "checkpoint.bin";
  const std::string hash = case_hash(scene);
  const fs::path checkpoint_hash = req.dir / "checkpoint.hash";
  if (fs::exists(checkpoint) && fs::exists(checkpoint_hash) && read_text(checkpoint_hash) == hash) {
    try {
      sim.load_checkpoint(checkpoint);
      spdlog::info("{}: resuming from its checkpoint at t = {:.4g} s", req.id, sim.time());
    } catch (const engine::SetupError &e) {
      // e.g. written by another version: the case starts again from its settled heap (a half-read
      // checkpoint leaves the simulation unusable, so it is built anew)
      spdlog::warn("{}: its checkpoint cannot be resumed ({}); the case starts again", req.id, e.what());
      std::error_code ec;
      fs::remove(checkpoint, ec);
      fs::remove(checkpoint_hash, ec);
      return spread<Real>(req, reg);
    }
  }
  const auto spreader = spreader_plugin.description();
  const double duration = spreader.duration + scene.time.relax;
  const double interval = scene.time.checkpoint_interval;
  const int snapshots = static_cast<int>(scene.time.snapshots);
  auto last_checkpoint = std::chrono::steady_clock::now();
  const auto t0 = last_checkpoint;
  const double steps_before = double(sim.step_count());
  // The checkpoint before its hash: a crash between the two leaves no hash or another scene's (the
  // case starts again), never this scene's hash beside another scene's checkpoint.
  auto save_checkpoint = [&] {
    sim.save_checkpoint(checkpoint);
    write_atomic(checkpoint_hash, hash);
  };
  std::vector<engine::SeriesEntry> series;
  nlohmann::json series_record = nlohmann::json::array();  // with the spreader's pose, for frames
  auto pose_at = [&](double t) { return to_json(spreader_plugin.pose(t)); };
  int next_snapshot = 1;
  // resumed: the snapshots written before the checkpoint stay in the series (their time is in the file)
  while (snapshots > 0 && next_snapshot <= snapshots && sim.time() >= duration * next_snapshot / (snapshots + 1)) {
    const std::string name = "series/state_" + std::to_string(next_snapshot) + ".vtp";
    if (fs::exists(req.dir / name)) {
      const double t = engine::read_vtp(req.dir / name).time;
      series.push_back({t, name});
      series_record.push_back({{"time", t}, {"file", name}, {"spreader", pose_at(t)}});
    }
    ++next_snapshot;
  }
  // one snapshot time per interval; callbacks every 100 steps are cheap against the step cost
  bool ok = run_spreading(
      sim, spreader_plugin, scene, duration,
      [&](const engine::Simulation<Real> &s) {
        const auto now = std::chrono::steady_clock::now();
        if (req.progress) req.progress(0.1 + 0.9 * s.time() / duration, "");
        if (next_snapshot <= snapshots && s.time() >= duration * next_snapshot / (snapshots + 1)) {
          const std::string name = "series/state_" + std::to_string(next_snapshot) + ".vtp";
          fs::create_directories(req.dir / "series");
          engine::write_vtp(req.dir / name, s.state(), s.time());
          series.push_back({s.time(), name});
          series_record.push_back({{"time", s.time()}, {"file", name}, {"spreader", pose_at(s.time())}});
          ++next_snapshot;
        }
        if (stop_requested()) return false;
        if (std::chrono::duration<double>(now - last_checkpoint).count() > interval) {
          save_checkpoint();
          last_checkpoint = now;
        }
        return true;
      },
      100);
  if (!ok) {
    save_checkpoint();
    throw Interrupted("interrupted: " + req.id + " saved its checkpoint at t = " + fmt::format("{:.4g}", sim.time()) +
                      " s; run the same command again to resume");
  }
  const ParticleSet state = sim.state();
  engine::write_vtp(req.dir / "state.vtp", state, sim.time());
  if (!series.empty()) {
    series.push_back({sim.time(), "state.vtp"});
    series_record.push_back({{"time", sim.time()}, {"file", "state.vtp"}, {"spreader", pose_at(sim.time())}});
    engine::write_pvd(req.dir / "series.pvd", series);
  }
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const auto &c = sim.counters();
  nlohmann::json out = {
      {"id", req.id},
      {"hash", hash},
      {"status", "done"},
      {"inputs", req.inputs},
      {"particles_start", heap.size()},
      {"particles_end", state.size()},
      {"removed", sim.removed_count()},
      {"steps", sim.step_count()},
      {"dt", sim.dt()},
      {"dt_critical", sim.critical_dt()},
      {"simulated_time", sim.time()},
      {"wall_seconds_last_run", wall},
      {"particle_steps_per_second", c.particle_steps_per_second()},
      {"list_builds", c.list_builds},
      {"steps_this_run", double(sim.step_count()) - steps_before},
      {"rotation_integrated", sim.rotation_integrated()},
      {"precision", precision_name(scene.precision)},
      {"spreader", to_json(spreader)},
      {"spreader_end", pose_at(sim.time())},
  };
  if (!series_record.empty()) out["series"] = series_record;
  // what case_finished checks on a re-run: a state damaged or replaced since makes the case run again
  const std::string state_text = read_text(req.dir / "state.vtp");
  out["state_bytes"] = state_text.size();
  out["state_hash"] = stable_hash(state_text);
  write_atomic(req.dir / "case.json", out.dump(2) + "\n");
  std::error_code ec;
  fs::remove(checkpoint, ec);
  fs::remove(checkpoint_hash, ec);
  return out;
}

}  // namespace

std::string case_hash(const Scene &scene) {
  nlohmann::json s = to_json(scene);
  s["time"].erase("checkpoint_interval");
  s.erase("threads");
  s.erase("backend");
  return stable_hash(s.dump());
}

std::string heap_hash(const Scene &scene, PluginRegistry &registry) {
  const nlohmann::json all = to_json(scene);
  nlohmann::json s = {{"powder", all["powder"]},   {"domain", all["domain"]},
                      {"contact", all["contact"]}, {"substrate", all["substrate"]},
                      {"gravity", all["gravity"]}, {"precision", all["precision"]},
                      {"time", all["time"]}};
  for (const char *k : {"relax", "checkpoint_interval", "snapshots"}) s["time"].erase(k);
  // The spreader as the heap sees it: its law and its body at rest, as it describes itself (its
  // motion, e.g. a speed or a rotation, does not change the heap).
  nlohmann::json body = to_json(describe_spreader(scene, registry, "scene.json"));
  for (const char *k : {"end", "speed", "duration"}) body.erase(k);
  s["spreader"] = {{"use", scene.spreader.use}, {"law", scene.spreader.law}, {"at_rest", body}};
  return stable_hash(s.dump());
}

bool case_finished(const fs::path &dir, const std::string &hash) {
  std::error_code ec;
  if (!fs::exists(dir / "case.json", ec) || !fs::exists(dir / "state.vtp", ec)) return false;
  try {
    const auto j = nlohmann::json::parse(read_text(dir / "case.json"));
    if (j.value("hash", "") != hash || j.value("status", "") != "done") return false;
    if (!j.contains("state_bytes")) return true;  // written before the state was fingerprinted
    if (fs::file_size(dir / "state.vtp", ec) != j["state_bytes"].get<std::uintmax_t>() || ec) return false;
    return stable_hash(read_text(dir / "state.vtp")) == j.value("state_hash", "");
  } catch (...) {
    return false;
  }
}

nlohmann::json run_case(const CaseRequest &request, PluginRegistry &registry) {
  fs::create_directories(request.dir);
  fs::create_directories(request.heaps);
  if (request.threads > 0) omp_set_num_threads(request.threads);
  CaseRequest effective = request;  // the scene the engine runs: coarse graining applied
  effective.scene = coarse_grained(request.scene, registry);
  if (effective.scene.precision == Precision::float32) return spread<float>(effective, registry);
  return spread<double>(effective, registry);
}

}  // namespace spreadmap
