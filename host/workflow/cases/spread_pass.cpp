#include "workflow/cases/spread_pass.hpp"

#include <spdlog/spdlog.h>

#include <chrono>
#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "core/files.hpp"
#include "core/stop.hpp"
#include "engine/errors.hpp"
#include "engine/simulation.hpp"
#include "engine/vtp_io.hpp"
#include "workflow/spreading/case_setup.hpp"

namespace spreadmap {
namespace {

using engine::ParticleSet;

// The pass's checkpoint in its folder: checkpoint.bin, and checkpoint.hash naming the scene it is of.
struct PassCheckpoint {
  fs::path file, hash_file;
  std::string hash;

  bool of_this_scene() const { return fs::exists(file) && fs::exists(hash_file) && read_text(hash_file) == hash; }

  // The checkpoint before its hash: a crash between the two leaves no hash or another scene's (the
  // case starts again), never this scene's hash beside another scene's checkpoint.
  template <class Real> void save(engine::Simulation<Real> &sim) const {
    sim.save_checkpoint(file);
    write_atomic(hash_file, hash);
  }

  void remove() const {
    std::error_code ec;
    fs::remove(file, ec);
    fs::remove(hash_file, ec);
  }
};

// Resumes `sim` from the checkpoint when it is of this scene. False when it cannot be resumed: it is
// removed, and the caller builds the simulation anew.
template <class Real>
bool resume_if_checkpointed(engine::Simulation<Real> &sim, const PassCheckpoint &checkpoint, const std::string &name) {
  if (!checkpoint.of_this_scene()) return true;
  try {
    sim.load_checkpoint(checkpoint.file);
    spdlog::info("{}: resuming from its checkpoint at t = {:.4g} s", name, sim.time());
  } catch (const engine::SetupError &e) {
    // e.g. written by another version: the pass starts again from its settled start (a half-read
    // checkpoint leaves the simulation unusable, so it is built anew)
    spdlog::warn("{}: its checkpoint cannot be resumed ({}); the case starts again", name, e.what());
    checkpoint.remove();
    return false;
  }
  return true;
}

// The pass's snapshots: series/state_K.vtp at K / (snapshots + 1) of its duration, each recorded with
// its time and the spreader's pose then (for case.json, series.pvd and the frames).
class PassSnapshots {
 public:
  PassSnapshots(const fs::path &dir, const scene::BoundSpreader &spreader, double duration, int snapshots)
      : dir_(dir), spreader_(spreader), duration_(duration), snapshots_(snapshots) {}

  nlohmann::json pose_at(double t) const { return to_json(spreader_.pose(t)); }

  // resumed: the snapshots written before the checkpoint stay in the series (their time is in the file)
  void read_back_written(double now) {
    while (snapshots_ > 0 && next_ <= snapshots_ && now >= due_time()) {
      const std::string file = file_name();
      if (fs::exists(dir_ / file)) add(engine::read_vtp(dir_ / file).time, file);
      ++next_;
    }
  }

  template <class Real> void take_if_due(const engine::Simulation<Real> &s) {
    if (!(next_ <= snapshots_ && s.time() >= due_time())) return;
    const std::string file = file_name();
    fs::create_directories(dir_ / "series");
    engine::write_vtp(dir_ / file, s.state(), s.time());
    add(s.time(), file);
    ++next_;
  }

  // The pass's end state closes the series (when it has snapshots) in series.pvd.
  void close(double end_time) {
    if (series_.empty()) return;
    add(end_time, "state.vtp");
    engine::write_pvd(dir_ / "series.pvd", series_);
  }

  const nlohmann::json &record() const { return record_; }

 private:
  double due_time() const { return duration_ * next_ / (snapshots_ + 1); }
  std::string file_name() const { return "series/state_" + std::to_string(next_) + ".vtp"; }
  void add(double t, const std::string &file) {
    series_.push_back({t, file});
    record_.push_back({{"time", t}, {"file", file}, {"spreader", pose_at(t)}});
  }

  fs::path dir_;
  const scene::BoundSpreader &spreader_;
  double duration_;
  int snapshots_;
  int next_ = 1;
  std::vector<engine::SeriesEntry> series_;
  nlohmann::json record_ = nlohmann::json::array();
};

// What the pass does at each callback: reports its progress, takes the snapshots that are due and
// saves the checkpoint every `interval` wall-clock seconds; false (stop) on SIGINT/SIGTERM. It holds
// references only, so that the copies std::function makes share one state.
template <class Real> struct PassStepCallback {
  engine::Simulation<Real> &sim;
  const PassCheckpoint &checkpoint;
  PassSnapshots &snapshots;
  const std::function<void(double)> &progress;
  double duration, interval;
  std::chrono::steady_clock::time_point &last_checkpoint;

  bool operator()(const engine::Simulation<Real> &s) const {
    const auto now = std::chrono::steady_clock::now();
    if (progress) progress(s.time() / duration);
    snapshots.take_if_due(s);
    if (stop_requested()) return false;
    if (std::chrono::duration<double>(now - last_checkpoint).count() > interval) {
      checkpoint.save(sim);
      last_checkpoint = now;
    }
    return true;
  }
};

// What case.json keeps of a finished pass: its particles, steps, time step, speed and step profile,
// its precision and the spreader's description and end pose.
template <class Real>
nlohmann::json pass_record(engine::Simulation<Real> &sim, const ParticleSet &start, const ParticleSet &end,
                           const Scene &scene, const sm_spreader_description_v2 &spreader, double wall,
                           double steps_before, const nlohmann::json &spreader_end) {
  const auto &c = sim.counters();
  return {
      {"particles_start", start.size()},
      {"particles_end", end.size()},
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
      {"spreader_end", spreader_end},
  };
}

}  // namespace

template <class Real>
std::optional<Pass> spread_pass(const Scene &scene, PluginRegistry &reg, const ParticleSet &start, const fs::path &dir,
                                const fs::path &scene_file, const std::string &hash, const std::string &name,
                                const std::function<void(double)> &progress) {
  const auto run = make_spreading_run<Real>(scene, reg, start, scene_file);
  auto &sim = run->sim;
  const auto &spreader_plugin = run->spreader;

  const PassCheckpoint checkpoint{dir / "checkpoint.bin", dir / "checkpoint.hash", hash};
  if (!resume_if_checkpointed(sim, checkpoint, name)) return std::nullopt;
  const auto spreader = spreader_plugin.description();
  const double duration = spreader.duration + scene.time.relax;
  const double interval = scene.time.checkpoint_interval;
  auto last_checkpoint = std::chrono::steady_clock::now();
  const auto t0 = last_checkpoint;
  const double steps_before = double(sim.step_count());
  PassSnapshots snapshots(dir, spreader_plugin, duration, static_cast<int>(scene.time.snapshots));
  snapshots.read_back_written(sim.time());
  // one snapshot time per interval; callbacks every 100 steps are cheap against the step cost
  bool ok = run_spreading(
      sim, spreader_plugin, scene, duration,
      PassStepCallback<Real>{sim, checkpoint, snapshots, progress, duration, interval, last_checkpoint}, 100);
  if (!ok) {
    checkpoint.save(sim);
    throw Interrupted("interrupted: " + name + " saved its checkpoint at t = " + fmt::format("{:.4g}", sim.time()) +
                      " s; run the same command again to resume");
  }
  Pass pass{sim.state(), {}};
  engine::write_vtp(dir / "state.vtp", pass.state, sim.time());
  snapshots.close(sim.time());
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  pass.record = pass_record(sim, start, pass.state, scene, spreader, wall, steps_before, snapshots.pose_at(sim.time()));
  if (!snapshots.record().empty()) pass.record["series"] = snapshots.record();
  return pass;
}

template std::optional<Pass> spread_pass<double>(const Scene &, PluginRegistry &, const ParticleSet &, const fs::path &,
                                                 const fs::path &, const std::string &, const std::string &,
                                                 const std::function<void(double)> &);
template std::optional<Pass> spread_pass<float>(const Scene &, PluginRegistry &, const ParticleSet &, const fs::path &,
                                                const fs::path &, const std::string &, const std::string &,
                                                const std::function<void(double)> &);

}  // namespace spreadmap
