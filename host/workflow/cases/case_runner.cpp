#include "workflow/cases/case_runner.hpp"

#include <omp.h>

#include <optional>
#include <nlohmann/json.hpp>

#include "workflow/cases/case_record.hpp"
#include "workflow/spreading/coarse_grain.hpp"
#include "workflow/cases/heap_cache.hpp"
#include "workflow/spreading/layer_feed.hpp"
#include "workflow/cases/layers.hpp"
#include "workflow/cases/machine_layers.hpp"
#include "workflow/cases/spread_pass.hpp"

namespace spreadmap {
namespace {

using engine::ParticleSet;

// One pass onto the flat plate, or onto the rough substrate's spheres when the scene has them.
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
  return write_finished_record(req.dir, "case.json", out);
}

}  // namespace

nlohmann::json run_case(const CaseRequest &request, PluginRegistry &registry) {
  fs::create_directories(request.dir);
  fs::create_directories(request.heaps);
  if (request.threads > 0) omp_set_num_threads(request.threads);
  CaseRequest effective = request;  // the scene the engine runs: coarse graining applied
  effective.scene = coarse_grained(request.scene, registry);
  const bool single = effective.scene.precision == Precision::float32;
  if (effective.scene.machine)
    return single ? spread_machine_layers<float>(effective, registry) : spread_machine_layers<double>(effective, registry);
  const bool layers = effective.scene.layers.count > 1;
  if (single) return layers ? spread_layers<float>(effective, registry) : spread_one_layer<float>(effective, registry);
  return layers ? spread_layers<double>(effective, registry) : spread_one_layer<double>(effective, registry);
}

}  // namespace spreadmap
