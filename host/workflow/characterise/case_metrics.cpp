#include "workflow/characterise/case_metrics.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <spreadmap/params.hpp>
#include <nlohmann/json.hpp>
#include <yaml-cpp/yaml.h>

#include "core/files.hpp"
#include "core/heightmap_vti.hpp"
#include "core/schema.hpp"
#include "core/units.hpp"
#include "workflow/figures/stage_figures.hpp"
#include "workflow/spreading/substrate_roughness.hpp"
#include "workflow/spreading/case_setup.hpp"
#include "workflow/cases/case_runner.hpp"
#include "workflow/stage/plugin_needs.hpp"
#include "workflow/spreading/layer_feed.hpp"
#include "workflow/spreading/machine_layout.hpp"
#include "workflow/spreading/powder_sizes.hpp"

namespace spreadmap {
namespace {

// The stage's own settings; the rest of its mapping are the metrics plugin's parameters.
constexpr sm_param_v1 characterise_schema[] = {
    text("use", "", "the metrics plugin (spreadmap plugins --kind metrics; default: the first that declares V_s and "
                    "R_q); its parameters sit beside these"),
    table("region", "the measured area {x: [14 mm, 24 mm], y: [0 mm, 2.5 mm]} (default: the spreader's path)"),
    table("render", "true, false or the figure's settings {width: 1920, vector: pdf}"),
};

std::set<std::string> host_keys() {
  std::set<std::string> out;
  for (const auto &p : characterise_schema) out.insert(p.name);
  return out;
}

void read_bounds(const YAML::Node &n, const std::string &file, const std::string &key, double &lo, double &hi,
                 Diagnostics &diag) {
  if (!n) return;
  if (!n.IsSequence() || n.size() != 2) {
    diag.error(Location::of(file, n), key, "must be a pair [low, high] of lengths", "e.g. [14 mm, 24 mm]");
    return;
  }
  try {
    const double a = parse_in(n[0].as<std::string>(), "m"), b = parse_in(n[1].as<std::string>(), "m");
    lo = a;
    hi = b;
  } catch (const std::exception &e) {
    diag.error(Location::of(file, n), key, e.what(), "write lengths with units, e.g. [14 mm, 24 mm]");
  }
}

// A machine's layer k is measured in its platform's frame: heights above the platform (which dropped
// k x thickness below the plates), the spreader's lower edge k x thickness + gap above it. Only the
// powder over the measured region (and a largest diameter beside it) is shown to the metrics: the
// reservoir's rests on the piston, not on the platform, and is no part of the layer.
void on_platform(const Scene &scene, int layer, engine::ParticleSet &particles, LayerRequest &rq) {
  const double lift = -machine_layout(scene).platform_top(layer);
  const double beside = size_distribution(scene.powder).upper();
  particles = engine::select_particles(particles, [&](std::size_t i) {
    return particles.x[i] >= rq.region.x0 - beside && particles.x[i] <= rq.region.x1 + beside;
  });
  for (double &z : particles.z) z += lift;
  rq.gap += lift;
}

// Layer k (1..count) of a multi-layer case is read from its layer_K folder: the whole bed after k
// passes, heights from the plate (z = 0), the gap the raised one (gap + drop), so packing and solid
// thickness stay consistent. layer_height = mean height - the platform's drop: the powder's mean top
// above the lowered platform's nominal place, as the spreader sees it (layer 1: mean height).
// Layer 0 is a single pass, read from the case folder itself. On a rough substrate its mean plane
// takes the plate's place: heights and the gap are measured from it, and its spheres (fixed in the
// state) are ground, not layer.
nlohmann::json evaluate(PluginRegistry &registry, const CharacteriseSettings &settings, const fs::path &case_dir,
                        const std::string &id, const std::string &key, int layer) {
  const Scene scene = read_scene_file(case_dir / "scene.json");
  const fs::path dir = layer ? case_dir / layer_folder(layer) : case_dir;
  auto particles = read_particle_file(dir / "state.vtp");
  LayerRequest rq = settings.request;
  rq.region = settings.region;
  if (scene.domain.periodic_y) rq.periodic_y = std::make_pair(0.0, scene.domain.width);
  if (settings.y_across_case && scene.domain.periodic_y) rq.region.y0 = 0, rq.region.y1 = scene.domain.width;
  // the spreader as it spread: its gap raised by the drop and by a rough substrate's mean plane
  const Scene spread_by = layer_scene(scene, std::max(layer, 1));
  take_spreader(rq, describe_spreader(spread_by, registry, case_dir / "scene.json"));
  rq.substrate_z = substrate_level(scene);  // 0 on the flat plate
  rq.gap -= rq.substrate_z;
  if (scene.machine) on_platform(scene, layer, particles, rq);
  LayerResult r = characterise_layer(registry, rq, particles);
  if (layer && r.metrics.value("mean_height", nlohmann::json()).is_number()) {
    r.metrics["layer_height"] = r.metrics["mean_height"].get<double>() - platform_drop(scene, layer);
    r.units["layer_height"] = "m";
  }
  for (const auto &w : r.warnings) spdlog::warn("{}: {}", id, w);
  if (!r.height.empty()) write_heightmap_vti(dir / "heightmap.vti", r.nx, r.ny, r.x0, r.y0, r.cell, r.height.data());
  nlohmann::json doc = {{"case", id},
                        {"key", key},
                        {"plugin", "metrics/" + rq.plugin},
                        {"region", {{"x", {rq.region.x0, rq.region.x1}}, {"y", {rq.region.y0, rq.region.y1}}}},
                        {"metrics", r.metrics},
                        {"units", r.units},
                        {"warnings", r.warnings}};
  if (layer) doc["layer"] = layer;
  if (!r.profiles.is_null()) doc["profiles"] = r.profiles;  // metrics.json only: metrics.csv holds scalars
  doc["digest"] = stable_hash(doc.dump());  // of everything else: what a later run checks before trusting it
  write_atomic(dir / "metrics.json", doc.dump(2) + "\n");
  if (settings.render) {
    const auto m = r.metrics;
    auto um = [&](const char *k) {
      return m.value(k, nlohmann::json()).is_number() ? m[k].get<double>() * 1e6 : std::nan("");
    };
    figures::heightmap({r.nx, r.ny, r.x0, r.y0, r.cell, r.height}, dir / "heightmap.png",
                       fmt::format("{}{}: mean height {:.0f} um, R_q {:.0f} um", id,
                                   layer ? " layer " + std::to_string(layer) : "", um("mean_height"), um("rq")));
  }
  return doc;
}

}  // namespace

SchemaView characterise_settings() { return {characterise_schema, std::size(characterise_schema)}; }

CharacteriseSettings read_characterise_settings(const Workflow &wf, const YAML::Node &cfg, const Scene *scene,
                                                PluginRegistry &registry, Diagnostics &diag) {
  CharacteriseSettings s;
  const std::string file = wf.file.string();
  const LoadedPlugin *plugin = nullptr;
  try {
    plugin = cfg["use"] && cfg["use"].IsScalar() ? &registry.get("metrics", cfg["use"].Scalar())
                                                 : &contract_metrics_plugin(registry, "the characterise stage");
    s.request.plugin = plugin->descriptor->name;
  } catch (const std::exception &e) {
    diag.error(Location::of(file, cfg["use"] ? cfg["use"] : cfg), "characterise.use", e.what());
  }
  if (plugin)
    s.request.params = validate_params(SchemaView::of(*plugin->descriptor), cfg, file, "characterise", diag, host_keys());
  if (!scene) return s;
  try {
    s.region = default_region(*scene, describe_spreader(*scene, registry, file));
  } catch (const std::exception &) {
    return s;  // the scene's own checks report the spreader's error
  }
  Region &region = s.region;
  if (const YAML::Node r = cfg["region"]) {
    if (!r.IsMap()) {
      diag.error(Location::of(file, r), "characterise.region", "must be a map",
                 "write region: {x: [14 mm, 24 mm], y: [0 mm, 2.5 mm]}");
    } else {
      for (const auto &kv : r)
        if (kv.first.as<std::string>() != "x" && kv.first.as<std::string>() != "y")
          diag.error(Location::of(file, kv.first), "characterise.region." + kv.first.as<std::string>(), "unknown key",
                     "known: x, y");
      read_bounds(r["x"], file, "characterise.region.x", region.x0, region.x1, diag);
      read_bounds(r["y"], file, "characterise.region.y", region.y0, region.y1, diag);
    }
  }
  s.y_across_case = scene->domain.periodic_y && !(cfg["region"] && cfg["region"]["y"]);
  const double length = scene->domain.length, width = scene->domain.width;
  if (region.x0 < 0 || region.x1 > length || region.y0 < 0 || region.y1 > width || region.x1 <= region.x0 ||
      region.y1 <= region.y0)
    diag.error(Location::of(file, cfg["region"] ? cfg["region"] : cfg), "characterise.region",
               fmt::format("x {}..{} mm, y {}..{} mm is not inside the domain (0..{} mm by 0..{} mm)", region.x0 * 1e3,
                           region.x1 * 1e3, region.y0 * 1e3, region.y1 * 1e3, length * 1e3, width * 1e3),
               "set characterise.region: {x: [A mm, B mm], y: [C mm, D mm]} inside the domain");
  s.style = figures::read_style(cfg["render"], true, false, file, "characterise.render", diag);
  s.render = s.style.on;
  return s;
}

namespace {
// True when metrics.json's digest is that of the rest of it: the metrics it holds are those computed.
bool sealed(nlohmann::json doc) {
  const auto it = doc.find("digest");
  if (it == doc.end() || !it->is_string()) return false;
  const std::string digest = *it;
  doc.erase("digest");
  return stable_hash(doc.dump()) == digest;
}

}  // namespace

std::string settings_hash(const CharacteriseSettings &s) {
  const Region &r = s.region;
  return stable_hash(s.request.params.dump() + nlohmann::json({r.x0, r.x1, r.y0, r.y1}).dump() + s.request.plugin +
                     (s.y_across_case ? "y across each case" : ""));
}

nlohmann::json case_metrics(PluginRegistry &registry, const CharacteriseSettings &settings, const fs::path &dir,
                            const std::string &id, const std::string &key, bool force, bool &evaluated, int layer) {
  const fs::path out = (layer ? dir / layer_folder(layer) : dir) / "metrics.json";
  nlohmann::json doc;
  if (!force && fs::exists(out)) {
    try {
      doc = nlohmann::json::parse(read_text(out));
      if (doc.value("key", "") != key) doc = nullptr;
      else if (!sealed(doc)) {
        spdlog::warn("{}: {} changed since it was written (its digest does not match); measuring again", id,
                     out.string());
        doc = nullptr;
      }
      // a height-map figure lost to a kill or a full disk is drawn again with its metrics
      const fs::path png = (layer ? dir / layer_folder(layer) : dir) / "heightmap.png";
      if (settings.render && figures::available() && !figures::whole_png(png)) doc = nullptr;
    } catch (...) {
      doc = nullptr;
    }
  }
  evaluated = doc.is_null();
  return evaluated ? evaluate(registry, settings, dir, id, key, layer) : doc;
}

}  // namespace spreadmap
