// characterise: the layer metrics of every finished case (metrics.json and heightmap.vti in the
// case folder), gathered in metrics.csv with one row per case and the unit of every column in
// metrics.units.json. A multi-layer case (scene.layers) has one row per layer, evaluated in its
// layer_K folder, and metrics.csv then a `layer` column after `case`. A case whose state and settings did not change is
// not evaluated again.
#include <spdlog/spdlog.h>

#include "analysis/table.hpp"
#include "core/error.hpp"
#include "core/files.hpp"
#include "core/heightmap_vti.hpp"
#include "core/schema.hpp"
#include "core/units.hpp"
#include "workflow/simulate/case_runner.hpp"
#include "workflow/simulate/case_setup.hpp"
#include "workflow/simulate/layer_feed.hpp"
#include "workflow/figures/figure_style.hpp"
#include "workflow/figures/stage_figures.hpp"
#include "workflow/characterise/layer_eval.hpp"
#include "workflow/stage.hpp"

namespace spreadmap {
namespace {

const std::set<std::string> host_keys = {"use", "region", "render"};

class CharacteriseStage : public Stage {
 public:
  void validate(const Workflow &wf, const StageEntry &entry, const Scene *scene, PluginRegistry &registry,
                Diagnostics &diag) override {
    const std::string file = wf.file.string();
    const YAML::Node &cfg = entry.config;
    request_.plugin = cfg["use"] ? cfg["use"].as<std::string>() : "layer";
    const LoadedPlugin *plugin = nullptr;
    try {
      plugin = &registry.get("metrics", request_.plugin);
    } catch (const std::exception &e) {
      diag.error(Location::of(file, cfg["use"] ? cfg["use"] : cfg), "characterise.use", e.what());
    }
    if (plugin)
      request_.params =
          validate_params(SchemaView::of(*plugin->descriptor), cfg, file, "characterise", diag, host_keys);
    if (!scene) return;
    try {
      region_ = default_region(*scene, describe_spreader(*scene, registry, file));
    } catch (const std::exception &) {
      return;  // the scene's own checks report the spreader's error
    }
    if (const YAML::Node r = cfg["region"]) {
      if (!r.IsMap()) {
        diag.error(Location::of(file, r), "characterise.region", "must be a map",
                   "write region: {x: [14 mm, 24 mm], y: [0 mm, 2.5 mm]}");
      } else {
        for (const auto &kv : r)
          if (kv.first.as<std::string>() != "x" && kv.first.as<std::string>() != "y")
            diag.error(Location::of(file, kv.first), "characterise.region." + kv.first.as<std::string>(), "unknown key",
                       "known: x, y");
        read_bounds(r["x"], file, "characterise.region.x", region_.x0, region_.x1, diag);
        read_bounds(r["y"], file, "characterise.region.y", region_.y0, region_.y1, diag);
      }
    }
    const double length = scene->domain.length, width = scene->domain.width;
    if (region_.x0 < 0 || region_.x1 > length || region_.y0 < 0 || region_.y1 > width || region_.x1 <= region_.x0 ||
        region_.y1 <= region_.y0)
      diag.error(
          Location::of(file, cfg["region"] ? cfg["region"] : entry.config), "characterise.region",
          fmt::format("x {}..{} mm, y {}..{} mm is not inside the domain (0..{} mm by 0..{} mm)", region_.x0 * 1e3,
                      region_.x1 * 1e3, region_.y0 * 1e3, region_.y1 * 1e3, length * 1e3, width * 1e3),
          "set characterise.region: {x: [A mm, B mm], y: [C mm, D mm]} inside the domain");
    style_ = figures::read_style(cfg["render"], true, false, file, "characterise.render", diag);
    render_ = style_.on;
  }

  void run(StageContext &ctx) override {
    figures::use_style(style_);
    const nlohmann::json manifest = ctx.run.manifest();
    if (!manifest.contains("cases") || manifest["cases"].empty())
      throw InputError("error: characterise: " + ctx.run.root().string() +
                       " has no simulated cases; run the simulate stage first (spreadmap run " + ctx.wf.file.string() +
                       ")");
    const std::string settings =
        stable_hash(request_.params.dump() + nlohmann::json({region_.x0, region_.x1, region_.y0, region_.y1}).dump() +
                    request_.plugin);
    std::vector<std::string> inputs;
    for (const auto &v : manifest["design"].value("variables", nlohmann::json::array())) inputs.push_back(v["name"]);

    std::vector<nlohmann::json> results;
    std::size_t evaluated = 0, missing = 0;
    for (const auto &c : manifest["cases"]) {
      const std::string id = c["id"];
      const fs::path dir = ctx.run.case_dir(id);
      if (!case_done(dir, c.value("hash", ""))) {
        ++missing;
        continue;
      }
      // one row per layer of a multi-layer case (layer 0: a single pass, as its own folder holds it)
      const int layers = static_cast<int>(read_scene_file(dir / "scene.json").layers.count);
      for (int layer = layers > 1 ? 1 : 0; layer <= (layers > 1 ? layers : 0); ++layer) {
        const fs::path out = (layer ? dir / layer_folder(layer) : dir) / "metrics.json";
        const std::string key =
            stable_hash(settings + c.value("hash", "") + (layer ? "/layer " + std::to_string(layer) : ""));
        nlohmann::json doc;
        if (!ctx.options.force && fs::exists(out)) {
          try {
            doc = nlohmann::json::parse(read_text(out));
            if (doc.value("key", "") != key) doc = nullptr;
          } catch (...) {
            doc = nullptr;
          }
        }
        if (doc.is_null()) {
          doc = evaluate(ctx, dir, id, key, layer);
          ++evaluated;
        }
        doc["inputs"] = c["inputs"];
        results.push_back(doc);
      }
    }
    if (missing)
      spdlog::warn("characterise: {} of {} cases have no finished state; run the simulate stage to complete them",
                   missing, manifest["cases"].size());
    write_table(ctx, inputs, manifest, results);
    spdlog::info("characterise: {} cases in metrics.csv ({} evaluated, {} up to date)", results.size(), evaluated,
                 results.size() - evaluated);
  }

 private:
  static void read_bounds(const YAML::Node &n, const std::string &file, const std::string &key, double &lo, double &hi,
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

  static bool case_done(const fs::path &dir, const std::string &hash) {
    std::error_code ec;
    if (!fs::exists(dir / "case.json", ec) || !fs::exists(dir / "state.vtp", ec)) return false;
    try {
      const auto j = nlohmann::json::parse(read_text(dir / "case.json"));
      return j.value("status", "") == "done" && (hash.empty() || j.value("hash", "") == hash);
    } catch (...) {
      return false;
    }
  }

  // Layer k of a multi-layer case is read from its folder. Its metrics are of the whole bed after k
  // passes, heights from the plate (z = 0), the gap the raised one (gap + drop): packing and solid
  // thickness stay consistent. layer_height = mean height - the platform's drop: the powder's mean
  // top above the lowered platform's nominal place, as the spreader sees it (layer 1: mean height).
  // Layer 0 is a single pass.
  nlohmann::json evaluate(StageContext &ctx, const fs::path &case_dir, const std::string &id, const std::string &key,
                          int layer) {
    const Scene scene = read_scene_file(case_dir / "scene.json");
    const fs::path dir = layer ? case_dir / layer_folder(layer) : case_dir;
    const auto particles = read_particle_file(dir / "state.vtp");
    LayerRequest rq = request_;
    rq.region = region_;
    if (scene.domain.periodic_y) rq.periodic_y = std::make_pair(0.0, scene.domain.width);
    const Scene spread_by = layer ? layer_scene(scene, layer) : scene;  // its gap raised by the drop
    take_spreader(rq, describe_spreader(spread_by, ctx.registry, case_dir / "scene.json"));
    LayerResult r = characterise_layer(ctx.registry, rq, particles);
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
    write_atomic(dir / "metrics.json", doc.dump(2) + "\n");
    if (render_) {
      const auto m = r.metrics;
      auto um = [&](const char *k) {
        return m.value(k, nlohmann::json()).is_number() ? m[k].get<double>() * 1e6 : std::nan("");
      };
      figures::heightmap(r, dir / "heightmap.png",
                         fmt::format("{}{}: mean height {:.0f} um, R_q {:.0f} um", id,
                                     layer ? " layer " + std::to_string(layer) : "", um("mean_height"), um("rq")));
    }
    return doc;
  }

  void write_table(StageContext &ctx, const std::vector<std::string> &inputs, const nlohmann::json &manifest,
                   const std::vector<nlohmann::json> &results) {
    std::vector<std::string> metrics = standard_metric_order();
    std::vector<std::string> cols = {"case"};
    const bool layered = std::any_of(results.begin(), results.end(), [](const auto &r) { return r.contains("layer"); });
    if (layered) cols.push_back("layer");  // multi-layer cases only: single-pass tables stay as they were
    cols.insert(cols.end(), inputs.begin(), inputs.end());
    // only the metrics some case has, standard ones first, then any extra a plugin reports
    std::vector<std::string> present;
    for (const auto &m : metrics)
      for (const auto &r : results)
        if (r["metrics"].contains(m)) {
          present.push_back(m);
          break;
        }
    for (const auto &r : results)
      for (auto &[k, v] : r["metrics"].items())
        if (std::find(present.begin(), present.end(), k) == present.end()) present.push_back(k);
    cols.insert(cols.end(), present.begin(), present.end());
    analysis::Table table(cols, "metrics.csv");
    nlohmann::json units = {{"case", ""}};
    if (layered) units["layer"] = "";
    for (const auto &v : manifest["design"].value("variables", nlohmann::json::array()))
      units[v["name"].get<std::string>()] = v["unit"];
    for (const auto &r : results) {
      std::vector<std::string> row = {r["case"]};
      if (layered) row.push_back(std::to_string(r.value("layer", 1)));
      for (const auto &in : inputs) row.push_back(analysis::Table::format(r["inputs"].value(in, std::nan(""))));
      for (const auto &m : present) {
        const auto &v = r["metrics"].value(m, nlohmann::json());
        row.push_back(v.is_number() ? analysis::Table::format(v.get<double>()) : "");  // empty = undefined
        if (r["units"].contains(m)) units[m] = r["units"][m];
      }
      table.add_row(row);
    }
    table.write_csv(ctx.run.metrics_csv().string());
    write_atomic(ctx.run.root() / "metrics.units.json", units.dump(2) + "\n");
  }

  LayerRequest request_;
  Region region_;
  figures::Style style_;
  bool render_ = true;
};

}  // namespace

std::unique_ptr<Stage> make_characterise_stage() { return std::make_unique<CharacteriseStage>(); }

}  // namespace spreadmap
