#include "workflow/case_once.hpp"
#include "workflow/coarse_grain.hpp"

#include <chrono>

#include "core/error.hpp"
#include "core/files.hpp"
#include "core/schema.hpp"
#include "core/stop.hpp"
#include "workflow/case_setup.hpp"
#include "workflow/figures.hpp"

namespace spreadmap {

nlohmann::json ensure_case(StageContext &ctx, const CaseRequest &req, bool render, bool &ran) {
  const std::string hash = case_hash(req.scene);
  ran = false;
  if (ctx.options.force || !case_finished(req.dir, hash)) {
    write_atomic(req.dir / "scene.json", coarse_grained(req.scene, ctx.registry).dump(2) + "\n");  // as the engine runs it
    const std::string start = RunDirectory::now_iso();
    const auto t0 = std::chrono::steady_clock::now();
    const nlohmann::json record = run_case(req, ctx.registry);
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    ctx.run.update_manifest([&](nlohmann::json &m) {
      if (!m.contains("cases")) m["cases"] = nlohmann::json::array();
      auto &cases = m["cases"];
      for (auto it = cases.begin(); it != cases.end(); ++it)
        if (it->value("id", "") == req.id) {
          cases.erase(it);
          break;
        }
      cases.push_back({{"id", req.id}, {"inputs", req.inputs}, {"hash", hash}, {"start", start},
                       {"end", RunDirectory::now_iso()}, {"wall_seconds", wall}, {"status", "done"}});
    });
    if (render)
      figures::snapshot(read_particle_file(req.dir / "state.vtp"), req.scene, record, req.dir / "snapshot.png",
                        figures::case_title(req.id, req.inputs));
    ran = true;
  } else {
    ctx.run.update_manifest([&](nlohmann::json &m) {
      if (!m.contains("cases")) m["cases"] = nlohmann::json::array();
      for (const auto &c : m["cases"])
        if (c.value("id", "") == req.id) return;
      m["cases"].push_back({{"id", req.id}, {"inputs", req.inputs}, {"hash", hash}, {"status", "done"}});
    });
  }
  if (stop_requested()) throw Interrupted("interrupted: finished cases are kept; run the same command again to resume");
  return nlohmann::json::parse(read_text(req.dir / "case.json"));
}

LayerResult measure_case_layer(PluginRegistry &registry, const nlohmann::json &scene, const fs::path &dir) {
  const LoadedPlugin &layer = registry.get("metrics", "layer");
  Diagnostics diag;
  LayerRequest lr;
  lr.params = validate_params(SchemaView::of(*layer.descriptor), YAML::Node(), "<defaults>", "metrics/layer", diag);
  diag.throw_if_any();
  const auto spreader = describe_spreader(scene, registry, dir / "scene.json");
  lr.region = default_region(scene, spreader);
  if (scene["domain"]["periodic_y"].get<bool>()) lr.periodic_y = std::make_pair(0.0, scene["domain"]["width"].get<double>());
  take_spreader(lr, spreader);
  return characterise_layer(registry, lr, read_particle_file(dir / "state.vtp"));
}

}  // namespace spreadmap
