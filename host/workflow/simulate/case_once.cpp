#include "workflow/simulate/case_once.hpp"

#include "workflow/run/run_dir.hpp"

#include "core/error.hpp"
#include "core/files.hpp"
#include "core/schema.hpp"
#include "core/stop.hpp"
#include "workflow/stage/plugin_needs.hpp"
#include "workflow/spreading/substrate_roughness.hpp"
#include "workflow/spreading/case_setup.hpp"
#include "workflow/spreading/coarse_grain.hpp"
#include "workflow/executors/local_executor.hpp"
#include <nlohmann/json.hpp>
#include <yaml-cpp/yaml.h>

namespace spreadmap {

nlohmann::json ensure_case(StageContext &ctx, const CaseRequest &req, bool render, bool &ran,
                           const std::string &stage) {
  const std::string hash = case_hash(req.scene);
  ran = ctx.options.force || !case_finished(req.dir, hash);
  ctx.run.update_manifest([&](nlohmann::json &m) {
    if (!m.contains("cases")) m["cases"] = nlohmann::json::array();
    auto &cases = m["cases"];
    for (auto it = cases.begin(); it != cases.end(); ++it)
      if (it->value("id", "") == req.id) {
        if (!ran) return;  // finished: its record stays
        cases.erase(it);
        break;
      }
    cases.push_back({{"id", req.id}, {"inputs", req.inputs}, {"hash", hash}});  // the executor adds the outcome
    if (!ran) cases.back()["status"] = "done";
  });
  if (ran) {
    write_scene_file(req.dir / "scene.json", coarse_grained(req.scene, ctx.registry));  // as the engine runs it
    CaseBatch batch{{{0, req, render}}, 1, stage};
    LocalExecutor(1, ctx.options.case_threads).run_cases(batch, ctx);
  }
  if (stop_requested()) throw Interrupted("interrupted: finished cases are kept; run the same command again to resume");
  return nlohmann::json::parse(read_text(req.dir / "case.json"));
}

LayerResult measure_case_layer(PluginRegistry &registry, const Scene &scene, const fs::path &dir) {
  const LoadedPlugin &metrics = contract_metrics_plugin(registry, "the adaptive design");
  Diagnostics diag;
  LayerRequest lr;
  lr.plugin = metrics.descriptor->name;
  lr.params = validate_params(SchemaView::of(*metrics.descriptor), YAML::Node(), "<defaults>", metrics.id(), diag);
  diag.throw_if_any();
  const auto spreader = describe_spreader(scene, registry, dir / "scene.json");
  lr.region = default_region(scene, spreader);
  if (scene.domain.periodic_y) lr.periodic_y = std::make_pair(0.0, scene.domain.width);
  take_spreader(lr, spreader);  // its gap above the substrate's mean plane, as the user gave it
  lr.substrate_z = substrate_level(coarse_grained(scene, registry));  // 0 on the flat plate
  return characterise_layer(registry, lr, read_particle_file(dir / "state.vtp"));
}

}  // namespace spreadmap
