#include "workflow/calibrate/bulk_test.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <chrono>
#include <fstream>
#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "core/files.hpp"
#include "core/stop.hpp"
#include "workflow/scene/scene_run.hpp"

namespace spreadmap::calibrate {
namespace {

nlohmann::json parameters_json(const std::vector<ParameterRange> &names, const std::vector<double> &values) {
  nlohmann::json j = nlohmann::json::object();
  for (std::size_t k = 0; k < names.size(); ++k) j[names[k].name] = values[k];
  return j;
}

// What a cached run depends on besides the parameters: the scene file's text and how it is measured.
// (Files the scene names, such as a particle CSV, are not included.)
std::string run_key(const BulkTest &test) {
  std::ifstream in(test.scene, std::ios::binary);
  const std::string text((std::istreambuf_iterator<char>(in)), {});
  return fmt::format("{:016x}/{}/{}", std::hash<std::string>{}(text),
                     test.measure == Measure::heap_angle ? "heap_angle" : "drum_angle", test.plate_z);
}

AngleFit fit_from(const nlohmann::json &j) {
  AngleFit a;
  a.angle_deg = j.at("angle_deg");
  a.spread_deg = j.at("spread_deg");
  a.uncertainty_deg = j.at("uncertainty_deg");
  a.parts_deg = j.at("parts_deg").get<std::vector<double>>();
  a.points = j.at("points");
  return a;
}

}  // namespace

BulkResult run_bulk_test(const BulkTest &test, const std::vector<ParameterRange> &names,
                         const std::vector<double> &values, const std::filesystem::path &record,
                         PluginRegistry &registry) {
  const nlohmann::json params = parameters_json(names, values);
  const std::string key = run_key(test);
  if (std::filesystem::exists(record)) {
    std::ifstream in(record);
    const auto j = nlohmann::json::parse(in, nullptr, false);
    if (!j.is_discarded() && j.value("scene", "") == test.scene.string() && j.value("key", "") == key &&
        j.value("parameters", nlohmann::json()) == params) {
      BulkResult r;
      r.angle = fit_from(j);
      r.particles = j.value("particles", std::size_t(0));
      r.steps = j.value("steps", std::uint64_t(0));
      r.wall_seconds = j.value("wall_seconds", 0.0);
      r.reused = true;
      return r;
    }
  }
  auto loaded = scene::load_scene(test.scene, registry);
  for (std::size_t k = 0; k < names.size(); ++k) loaded.scene.pair_law[names[k].name] = values[k];
  const auto t0 = std::chrono::steady_clock::now();
  auto run = scene::build_scene<double>(loaded, registry);
  const auto keep_going = [](const engine::Simulation<double> &) { return !stop_requested(); };
  // A heap is measured once it has come to rest, at the end; a drum's surface keeps moving, so it is
  // measured at every output time of the run's second half and the fits are pooled.
  std::vector<double> times = {loaded.scene.run.duration};
  if (test.measure == Measure::drum_angle) {
    times.clear();
    for (double t : loaded.scene.run.output_times)
      if (t >= 0.5 * loaded.scene.run.duration) times.push_back(t);
  }
  std::vector<AngleFit> fits;
  engine::ParticleSet state;
  for (double t : times) {
    if (!scene::advance_scene(*run, t, keep_going))
      throw Interrupted(fmt::format("interrupted in {} at {}; the finished runs are kept", test.name, params.dump()));
    state = run->sim->state();
    fits.push_back(test.measure == Measure::heap_angle ? heap_angle(state, test.plate_z) : bed_angle(state, 4));
  }
  BulkResult r;
  r.angle = pooled(fits);
  r.particles = state.size();
  r.steps = run->sim->step_count();
  r.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const nlohmann::json j = {{"test", test.name},
                            {"scene", test.scene.string()},
                            {"key", key},
                            {"parameters", params},
                            {"angle_deg", r.angle.angle_deg},
                            {"spread_deg", r.angle.spread_deg},
                            {"uncertainty_deg", r.angle.uncertainty_deg},
                            {"parts_deg", r.angle.parts_deg},
                            {"points", r.angle.points},
                            {"particles", r.particles},
                            {"steps", r.steps},
                            {"wall_seconds", r.wall_seconds}};
  write_atomic(record, j.dump(2) + "\n");
  return r;
}

}  // namespace spreadmap::calibrate
