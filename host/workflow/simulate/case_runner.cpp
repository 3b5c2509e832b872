#include "workflow/simulate/case_runner.hpp"

#include <omp.h>
#include <spdlog/spdlog.h>
#include <spreadmap/contact.hpp>
#include <spreadmap/geometry.hpp>

#include <chrono>
#include <cmath>
#include <map>
#include <mutex>
#include <optional>

#include "core/error.hpp"
#include "engine/errors.hpp"
#include "workflow/simulate/coarse_grain.hpp"
#include "core/files.hpp"
#include "core/stop.hpp"
#include "engine/simulation.hpp"
#include "engine/vtp_io.hpp"
#include "scene/coverage.hpp"
#include "workflow/simulate/case_setup.hpp"
#include "workflow/scene/substrate_roughness.hpp"
#include "workflow/simulate/layer_feed.hpp"

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
  // The heap is sealed by the hash of its file (heap_<key>.hash, written after it): a heap changed or
  // damaged since is settled again, never reused, so no case starts from a heap that no longer is.
  const fs::path seal = req.heaps / ("heap_" + key + ".hash");
  if (fs::exists(file)) {
    const std::string text = read_text(file);
    if (fs::exists(seal) && read_text(seal) == stable_hash(text)) {
      spdlog::debug("{}: reusing settled heap {}", req.id, file.string());
      return engine::read_vtp(file).particles;
    }
    spdlog::warn("{}: the settled heap {} {}; settling it again", req.id, file.string(),
                 fs::exists(seal) ? "changed since it was written (its hash does not match)" : "has no hash beside it");
  }
  ParticleSet heap = settle_heap<Real>(scene, reg, req.id, req.dir / "scene.json", [&req](double f) {
    if (req.progress) req.progress(0.1 * f, "settling");
  });
  engine::write_vtp(file, heap, 0.0);
  write_atomic(seal, stable_hash(read_text(file)));
  return heap;
}

// What one pass of the spreader leaves: its end state and the record case.json keeps of it.
struct Pass {
  ParticleSet state;
  nlohmann::json record;
};

// One pass of the spreader over `start` (settled), resumed from the checkpoint in `dir` when one of
// this `hash` is there; writes dir/state.vtp (and dir/series/ with snapshots). Empty when the
// checkpoint could not be resumed (it is removed: the caller starts the pass again). `name` names the
// pass in the log; `progress` gets the fraction of the pass done.
template <class Real>
std::optional<Pass> spread_pass(const Scene &scene, PluginRegistry &reg, const ParticleSet &start, const fs::path &dir,
                                const fs::path &scene_file, const std::string &hash, const std::string &name,
                                const std::function<void(double)> &progress) {
  const auto run = make_spreading_run<Real>(scene, reg, start, scene_file);
  auto &sim = run->sim;
  const auto &spreader_plugin = run->spreader;

  const fs::path checkpoint = dir / "checkpoint.bin";
  const fs::path checkpoint_hash = dir / "checkpoint.hash";
  if (fs::exists(checkpoint) && fs::exists(checkpoint_hash) && read_text(checkpoint_hash) == hash) {
    try {
      sim.load_checkpoint(checkpoint);
      spdlog::info("{}: resuming from its checkpoint at t = {:.4g} s", name, sim.time());
    } catch (const engine::SetupError &e) {
      // e.g. written by another version: the pass starts again from its settled start (a half-read
      // checkpoint leaves the simulation unusable, so it is built anew)
      spdlog::warn("{}: its checkpoint cannot be resumed ({}); the case starts again", name, e.what());
      std::error_code ec;
      fs::remove(checkpoint, ec);
      fs::remove(checkpoint_hash, ec);
      return std::nullopt;
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
    const std::string file = "series/state_" + std::to_string(next_snapshot) + ".vtp";
    if (fs::exists(dir / file)) {
      const double t = engine::read_vtp(dir / file).time;
      series.push_back({t, file});
      series_record.push_back({{"time", t}, {"file", file}, {"spreader", pose_at(t)}});
    }
    ++next_snapshot;
  }
  // one snapshot time per interval; callbacks every 100 steps are cheap against the step cost
  bool ok = run_spreading(
      sim, spreader_plugin, scene, duration,
      [&](const engine::Simulation<Real> &s) {
        const auto now = std::chrono::steady_clock::now();
        if (progress) progress(s.time() / duration);
        if (next_snapshot <= snapshots && s.time() >= duration * next_snapshot / (snapshots + 1)) {
          const std::string file = "series/state_" + std::to_string(next_snapshot) + ".vtp";
          fs::create_directories(dir / "series");
          engine::write_vtp(dir / file, s.state(), s.time());
          series.push_back({s.time(), file});
          series_record.push_back({{"time", s.time()}, {"file", file}, {"spreader", pose_at(s.time())}});
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
    throw Interrupted("interrupted: " + name + " saved its checkpoint at t = " + fmt::format("{:.4g}", sim.time()) +
                      " s; run the same command again to resume");
  }
  Pass pass{sim.state(), {}};
  engine::write_vtp(dir / "state.vtp", pass.state, sim.time());
  if (!series.empty()) {
    series.push_back({sim.time(), "state.vtp"});
    series_record.push_back({{"time", sim.time()}, {"file", "state.vtp"}, {"spreader", pose_at(sim.time())}});
    engine::write_pvd(dir / "series.pvd", series);
  }
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const auto &c = sim.counters();
  pass.record = {
      {"particles_start", start.size()},
      {"particles_end", pass.state.size()},
      {"removed", sim.removed_count()},
      {"steps", sim.step_count()},
      {"dt", sim.dt()},
      {"dt_critical", sim.critical_dt()},
      {"simulated_time", sim.time()},
      {"wall_seconds_last_run", wall},
      {"particle_steps_per_second", c.particle_steps_per_second()},
      {"list_builds", c.list_builds},
      {"step_profile_seconds",
       {{"integrate", c.profile.integrate},
        {"neighbours", c.profile.neighbours},
        {"pairs", c.profile.pairs},
        {"planes", c.profile.planes},
        {"geometries", c.profile.geometries},
        {"other", c.profile.other}}},
      {"steps_this_run", double(sim.step_count()) - steps_before},
      {"rotation_integrated", sim.rotation_integrated()},
      {"precision", precision_name(scene.precision)},
      {"spreader", to_json(spreader)},
      {"spreader_end", pose_at(sim.time())},
  };
  if (!series_record.empty()) pass.record["series"] = series_record;
  return pass;
}

// Writes `record` as dir/RECORD with the fingerprint of dir/state.vtp (what a re-run checks: a state
// damaged or replaced since makes it run again), then removes the pass's checkpoint.
nlohmann::json write_finished(const fs::path &dir, const std::string &record_name, nlohmann::json record) {
  const std::string state_text = read_text(dir / "state.vtp");
  record["state_bytes"] = state_text.size();
  record["state_hash"] = stable_hash(state_text);
  write_atomic(dir / record_name, record.dump(2) + "\n");
  std::error_code ec;
  fs::remove(dir / "checkpoint.bin", ec);
  fs::remove(dir / "checkpoint.hash", ec);
  return record;
}

// True when dir/RECORD is a finished result of this hash, its state.vtp intact.
bool finished(const fs::path &dir, const std::string &record_name, const std::string &hash) {
  std::error_code ec;
  if (!fs::exists(dir / record_name, ec) || !fs::exists(dir / "state.vtp", ec)) return false;
  try {
    const auto j = nlohmann::json::parse(read_text(dir / record_name));
    if (j.value("hash", "") != hash || j.value("status", "") != "done") return false;
    if (!j.contains("state_bytes")) return true;  // written before the state was fingerprinted
    if (fs::file_size(dir / "state.vtp", ec) != j["state_bytes"].get<std::uintmax_t>() || ec) return false;
    return stable_hash(read_text(dir / "state.vtp")) == j.value("state_hash", "");
  } catch (...) {
    return false;
  }
}

// Where a pass onto a bed starts (the rough substrate's spheres, or the layers spread before): the
// heap fed onto the bed and settled there under the raised spreader at rest (layer_feed.hpp). When
// the pass will resume from its checkpoint in `dir` (of this `hash`) the settling is skipped: the
// checkpoint replaces the start.
struct BedStart {
  ParticleSet start;
  std::size_t fed = 0;               // the heap's spheres fed onto the bed
  std::size_t removed_settling = 0;  // of those, the ones that left the domain while settling
  bool resumed = false;
};

template <class Real>
BedStart start_on_bed(const Scene &raised, PluginRegistry &reg, const CaseRequest &req, const std::string &name,
                      const fs::path &dir, const std::string &hash, const ParticleSet &bed, const ParticleSet &heap) {
  const ParticleSet fed_bed = fed_onto_bed(raised, reg, req.dir / "scene.json", bed, heap);
  BedStart out;
  out.fed = fed_bed.size() - bed.size();
  out.resumed = fs::exists(dir / "checkpoint.hash") && read_text(dir / "checkpoint.hash") == hash;
  out.start = out.resumed ? fed_bed : settle_on_bed<Real>(raised, reg, name, req.dir / "scene.json", fed_bed);
  out.removed_settling = fed_bed.size() - out.start.size();
  return out;
}

// What case.json records of a rough substrate: its spheres, their diameter, the mean plane of their
// tops and the R_q of the tops about it.
nlohmann::json substrate_record(const ParticleSet &substrate) {
  double level = 0, rq = 0;  // from the spheres at hand: generating the substrate again would cost as much
  for (std::size_t i = 0; i < substrate.size(); ++i) level += substrate.z[i] + substrate.radius[i];
  level /= double(substrate.size());
  for (std::size_t i = 0; i < substrate.size(); ++i) rq += std::pow(substrate.z[i] + substrate.radius[i] - level, 2);
  return {{"spheres", substrate.size()},
          {"sphere_diameter", 2 * substrate.radius.front()},
          {"mean_plane", level},
          {"rq", std::sqrt(rq / double(substrate.size()))}};
}

template <class Real> nlohmann::json spread_one_layer(const CaseRequest &req, PluginRegistry &reg) {
  const auto &scene = req.scene;
  const std::string hash = case_hash(scene);
  const ParticleSet substrate = substrate_spheres(scene);  // empty: the flat plate
  const Scene raised = layer_scene(scene, 1);              // `scene` on the flat plate
  std::optional<Pass> pass;
  std::optional<BedStart> on_substrate;
  while (!pass) {
    const ParticleSet heap = settled_heap<Real>(scene, reg, req);
    if (substrate.size() > 0)
      on_substrate = start_on_bed<Real>(raised, reg, req, req.id, req.dir, hash, substrate, heap);
    pass = spread_pass<Real>(raised, reg, on_substrate ? on_substrate->start : heap, req.dir, req.dir / "scene.json",
                             hash, req.id, [&req](double f) {
                               if (req.progress) req.progress(0.1 + 0.9 * f, "");
                             });
  }
  nlohmann::json out = pass->record;
  out["id"] = req.id;
  out["hash"] = hash;
  out["status"] = "done";
  out["inputs"] = req.inputs;
  if (on_substrate) {
    // resumed, the settling's losses are what the checkpoint's state lacks beyond the pass's own
    const std::size_t removed_settling = on_substrate->resumed ? on_substrate->start.size() - pass->state.size() -
                                                                     pass->record["removed"].get<std::size_t>()
                                                               : on_substrate->removed_settling;
    out["substrate"] = substrate_record(substrate);
    out["particles_fed"] = on_substrate->fed;
    out["removed_settling"] = removed_settling;
  }
  return write_finished(req.dir, "case.json", out);
}

// Layer upon layer (layer_feed.hpp): layer k's pass in cases/cNNN/layer_k/ (state.vtp, layer.json),
// each written once finished; a re-run skips the finished layers and resumes the one it was on. The
// case's state.vtp is the last layer's.
template <class Real> nlohmann::json spread_layers(const CaseRequest &req, PluginRegistry &reg) {
  const auto &scene = req.scene;
  const int count = static_cast<int>(scene.layers.count);
  const std::string hash = case_hash(scene);
  const ParticleSet heap = settled_heap<Real>(scene, reg, req);
  nlohmann::json layers = nlohmann::json::array();
  const ParticleSet substrate = substrate_spheres(scene);  // empty: the flat plate
  ParticleSet bed = substrate;
  std::size_t fed = 0;
  for (int k = 1; k <= count; ++k) {
    const fs::path dir = req.dir / layer_folder(k);
    const std::string name = req.id + " layer " + std::to_string(k);
    if (finished(dir, "layer.json", hash)) {
      spdlog::info("{}: finished before, read back", name);
      bed = engine::read_vtp(dir / "state.vtp").particles;
      layers.push_back(nlohmann::json::parse(read_text(dir / "layer.json")));
      fed += layers.back().value("particles_fed", std::size_t(0));
      continue;
    }
    fs::create_directories(dir);
    const Scene raised = layer_scene(scene, k);
    auto progress = [&](double f) {
      if (req.progress) req.progress(0.1 + 0.9 * (k - 1 + f) / count, "layer " + std::to_string(k));
    };
    std::optional<Pass> pass;
    std::size_t removed_settling = 0, fed_here = heap.size();
    while (!pass) {
      ParticleSet start = heap;
      bool resumed = false;
      if (k > 1 || bed.size() > 0) {  // onto the layers below, or onto the rough substrate
        BedStart on_bed = start_on_bed<Real>(raised, reg, req, name, dir, hash, bed, heap);
        start = std::move(on_bed.start);
        fed_here = on_bed.fed;
        removed_settling = on_bed.removed_settling;
        resumed = on_bed.resumed;
      }
      pass = spread_pass<Real>(raised, reg, start, dir, req.dir / "scene.json", hash, name, progress);
      // resumed, the settling's losses are what the checkpoint's state lacks beyond the pass's own
      if (pass && resumed)
        removed_settling = start.size() - pass->state.size() - pass->record["removed"].get<std::size_t>();
    }
    nlohmann::json record = pass->record;
    record["layer"] = k;
    record["hash"] = hash;
    record["status"] = "done";
    record["platform_drop"] = platform_drop(scene, k);
    record["particles_fed"] = fed_here;
    record["removed_settling"] = removed_settling;
    bed = std::move(pass->state);
    fed += fed_here;
    layers.push_back(write_finished(dir, "layer.json", record));
  }
  // the case's state: the last layer's, byte for byte
  write_atomic(req.dir / "state.vtp", read_text(req.dir / layer_folder(count) / "state.vtp"));
  const nlohmann::json &last = layers.back();
  std::size_t removed = 0;
  double steps = 0;
  for (const auto &l : layers) {
    removed += l.value("removed", std::size_t(0)) + l.value("removed_settling", std::size_t(0));
    steps += l.value("steps", 0.0);
  }
  nlohmann::json out = {{"id", req.id},
                        {"hash", hash},
                        {"status", "done"},
                        {"inputs", req.inputs},
                        {"layers", layers},
                        {"particles_start", heap.size()},
                        {"particles_fed", fed},
                        {"particles_end", bed.size()},
                        {"removed", removed},
                        {"steps", steps},
                        {"simulated_time", last["simulated_time"]},
                        {"precision", precision_name(scene.precision)},
                        {"spreader", last["spreader"]},
                        {"spreader_end", last["spreader_end"]}};
  if (substrate.size() > 0) out["substrate"] = substrate_record(substrate);
  return write_finished(req.dir, "case.json", out);
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
  s["substrate"].erase("roughness");  // the heap settles on the plate and is fed onto a substrate of spheres after
  s["substrate"].erase("height_map");
  for (const char *k : {"relax", "checkpoint_interval", "snapshots"}) s["time"].erase(k);
  // The spreader as the heap sees it: its law and its body at rest, as it describes itself (its
  // motion, e.g. a speed or a rotation, does not change the heap).
  nlohmann::json body = to_json(describe_spreader(scene, registry, "scene.json"));
  for (const char *k : {"end", "speed", "duration"}) body.erase(k);
  s["spreader"] = {{"use", scene.spreader.use}, {"law", scene.spreader.law}, {"at_rest", body}};
  return stable_hash(s.dump());
}

bool case_finished(const fs::path &dir, const std::string &hash) { return finished(dir, "case.json", hash); }

std::string layer_folder(int layer) { return "layer_" + std::to_string(layer); }

nlohmann::json run_case(const CaseRequest &request, PluginRegistry &registry) {
  fs::create_directories(request.dir);
  fs::create_directories(request.heaps);
  if (request.threads > 0) omp_set_num_threads(request.threads);
  CaseRequest effective = request;  // the scene the engine runs: coarse graining applied
  effective.scene = coarse_grained(request.scene, registry);
  const bool layered = effective.scene.layers.count > 1;
  if (effective.scene.precision == Precision::float32)
    return layered ? spread_layers<float>(effective, registry) : spread_one_layer<float>(effective, registry);
  return layered ? spread_layers<double>(effective, registry) : spread_one_layer<double>(effective, registry);
}

}  // namespace spreadmap
