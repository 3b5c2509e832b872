#include "workflow/spreading/case_scene.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "core/stop.hpp"
#include "workflow/spreading/case_setup.hpp"
#include "workflow/spreading/powder_sizes.hpp"

namespace spreadmap {

using scene::WallKind;
using scene::WallSpec;

WallSpec plane_wall(const std::string &name, const std::string &key, const std::array<double, 3> &point,
                    const std::array<double, 3> &normal, const nlohmann::json &law) {
  WallSpec w;
  w.kind = WallKind::plane;
  w.name = name;
  w.key_path = key;
  w.point = point;
  w.normal = normal;
  w.law = law;
  return w;
}

WallSpec spreader_wall(const Scene &scene, PluginRegistry &reg, double time_offset) {
  WallSpec w;
  w.kind = WallKind::spreader;
  w.name = reg.get("spreader", scene.spreader.use).id();
  w.key_path = "scene.spreader";
  w.spreader = {scene.spreader.use, scene.spreader.params, time_offset};
  w.law = scene.spreader.law;
  return w;
}

scene::LoadedScene case_scene(const Scene &spreading, const fs::path &scene_file) {
  scene::LoadedScene l;
  auto &s = l.scene;
  s.file = scene_file;
  s.name = "case";
  s.domain = make_domain(spreading);
  s.gravity = {0, 0, -spreading.gravity};
  s.law = spreading.contact.use;
  s.pair_law = spreading.contact.params;
  s.particles.density = spreading.powder.density;
  const TimeSettings &t = spreading.time;
  s.run.dt = t.step;
  s.run.safety = t.safety;
  s.run.skin = t.skin;
  s.run.overlap_limit = t.overlap_limit;
  s.run.sleep = t.sleep;
  s.run.sleep_speed = t.sleep_speed;
  s.run.log_engine = false;  // a workflow runs many cases: the engine's messages at debug
  s.backend = spreading.backend;
  return l;
}

double rest_shift(const Scene &scene) { return -(scene.powder.settle_time + 1.0); }

double heap_clearance(const Scene &scene) { return 0.05 * size_distribution(scene.powder).upper(); }

SettleRule powder_settle_rule(const Powder &powder) {
  return {0.3 * powder.settle_time, powder.settle_time, powder.settle_speed, powder.settle_fraction};
}

template <class Real>
engine::ParticleSet settle_scene(const scene::LoadedScene &settling, PluginRegistry &reg, const SettleRule &rule,
                                 const std::string &label, const std::string &what,
                                 const std::function<void(double)> &progress) {
  const auto run = scene::build_scene<Real>(settling, reg);
  auto &sim = *run->sim;
  sim.run_until(
      rule.max_time,
      [&](const engine::Simulation<Real> &s) {
        if (stop_requested()) return false;
        if (progress) progress(s.time() / rule.max_time);
        if (s.time() < rule.min_time) return true;
        const auto &a = s.arrays();
        return still_settling(rule, a.vx, a.vy, a.vz);
      },
      200);
  if (stop_requested())
    throw Interrupted("interrupted while settling the " + what + " of " + label +
                      ": run the same command again to resume");
  auto state = sim.state();
  spdlog::info("{}: {} settled after {:.3g} s ({} steps, {} removed)", label, what, sim.time(), sim.step_count(),
               sim.removed_count());
  return state;
}

template engine::ParticleSet settle_scene<double>(const scene::LoadedScene &, PluginRegistry &, const SettleRule &,
                                                  const std::string &, const std::string &,
                                                  const std::function<void(double)> &);
template engine::ParticleSet settle_scene<float>(const scene::LoadedScene &, PluginRegistry &, const SettleRule &,
                                                 const std::string &, const std::string &,
                                                 const std::function<void(double)> &);

}  // namespace spreadmap
