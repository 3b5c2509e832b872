#include "workflow/cases/machine_layers.hpp"

#include <spreadmap/sphere.hpp>

#include <optional>
#include <nlohmann/json.hpp>

#include "core/files.hpp"
#include "workflow/cases/case_record.hpp"
#include "workflow/cases/heap_cache.hpp"
#include "workflow/cases/layered_case.hpp"
#include "workflow/cases/spread_pass.hpp"
#include "workflow/spreading/layer_feed.hpp"
#include "workflow/spreading/machine_layout.hpp"
#include "workflow/spreading/machine_setup.hpp"

namespace spreadmap {

using engine::ParticleSet;

namespace {

// Solid volume of the spheres whose centre lies over [x0, x1) [m^3].
double solid_over(const ParticleSet &set, double x0, double x1) {
  double v = 0;
  for (std::size_t i = 0; i < set.size(); ++i)
    if (set.x[i] >= x0 && set.x[i] < x1) v += sphere_volume(2 * set.radius[i]);
  return v;
}

// What layer.json keeps of a machine's layer beside the pass's record: where the platform and the
// piston stood, the powder in the reservoir and the well after it.
nlohmann::json machine_record(const Scene &layer, const ParticleSet &start, const ParticleSet &end) {
  const MachineLayout l = machine_layout(layer);
  const int k = layer.machine->layer;
  return {{"platform_top", l.platform_top(k)},
          {"piston_top", l.piston_top(k)},
          {"reservoir_solid_start", solid_over(start, l.reservoir_from, l.reservoir_to)},
          {"reservoir_solid_end", solid_over(end, l.reservoir_from, l.reservoir_to)},
          {"well_solid", solid_over(end, l.well_from, l.well_to)}};
}

}  // namespace

template <class Real> nlohmann::json spread_machine_layers(const CaseRequest &req, PluginRegistry &reg) {
  const auto &scene = req.scene;
  const int count = static_cast<int>(scene.layers.count);
  const std::string hash = case_hash(scene);
  ParticleSet bed = settled_heap<Real>(scene, reg, req);  // the reservoir, filled and levelled
  const std::size_t filled = bed.size();
  nlohmann::json layers = nlohmann::json::array();
  for (int k = 1; k <= count; ++k) {
    const fs::path dir = req.dir / layer_folder(k);
    const std::string name = req.id + " layer " + std::to_string(k);
    if (auto finished = finished_layer(dir, hash, name)) {
      bed = std::move(*finished);
    } else {
      fs::create_directories(dir);
      const Scene layer = layer_scene(scene, k);
      auto progress = [&](double f) {
        if (req.progress) req.progress(0.1 + 0.9 * (k - 1 + f) / count, "layer " + std::to_string(k));
      };
      std::optional<Pass> pass;
      ParticleSet start;
      while (!pass) {
        // run again when the pass resumes from its checkpoint too (deterministic, and a few seconds):
        // the layer's record describes the powder the pass started from
        start = after_strokes<Real>(layer, reg, name, req.dir / "scene.json", bed);
        pass = spread_pass<Real>(layer, reg, start, dir, req.dir / "scene.json", hash, name, progress);
      }
      nlohmann::json record = pass->record;
      record.update(machine_record(layer, start, pass->state));
      record["layer"] = k;
      record["hash"] = hash;
      record["status"] = "done";
      record["platform_drop"] = platform_drop(scene, k);
      record["removed_strokes"] = bed.size() - start.size();
      bed = std::move(pass->state);
      write_finished_record(dir, "layer.json", record);
    }
    layers.push_back(nlohmann::json::parse(read_text(dir / "layer.json")));
  }
  return finish_layered_case(req, hash, layers, {{"particles_start", filled}, {"particles_end", bed.size()}});
}

template nlohmann::json spread_machine_layers<double>(const CaseRequest &, PluginRegistry &);
template nlohmann::json spread_machine_layers<float>(const CaseRequest &, PluginRegistry &);

}  // namespace spreadmap
