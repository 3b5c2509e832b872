#include "workflow/cases/layers.hpp"

#include <optional>
#include <nlohmann/json.hpp>

#include "core/files.hpp"
#include "workflow/cases/case_record.hpp"
#include "workflow/spreading/case_setup.hpp"
#include "workflow/cases/heap_cache.hpp"
#include "workflow/cases/layered_case.hpp"
#include "workflow/spreading/layer_feed.hpp"
#include "workflow/cases/spread_pass.hpp"

namespace spreadmap {

using engine::ParticleSet;

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
    if (auto finished = finished_layer(dir, hash, name)) {
      bed = std::move(*finished);
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
    layers.push_back(write_finished_record(dir, "layer.json", record));
  }
  nlohmann::json extra = {{"particles_start", heap.size()}, {"particles_fed", fed}, {"particles_end", bed.size()}};
  if (substrate.size() > 0) extra["substrate"] = substrate_record(substrate);
  return finish_layered_case(req, hash, layers, extra);
}

std::string layer_folder(int layer) { return "layer_" + std::to_string(layer); }

template BedStart start_on_bed<double>(const Scene &, PluginRegistry &, const CaseRequest &, const std::string &,
                                       const fs::path &, const std::string &, const ParticleSet &, const ParticleSet &);
template BedStart start_on_bed<float>(const Scene &, PluginRegistry &, const CaseRequest &, const std::string &,
                                      const fs::path &, const std::string &, const ParticleSet &, const ParticleSet &);
template nlohmann::json spread_layers<double>(const CaseRequest &, PluginRegistry &);
template nlohmann::json spread_layers<float>(const CaseRequest &, PluginRegistry &);

}  // namespace spreadmap
