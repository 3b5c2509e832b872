// characterise: the layer metrics of every finished case (metrics.json and heightmap.vti in the
// case folder), gathered in metrics.csv with one row per case and the unit of every column in
// metrics.units.json. A multi-layer case (scene.layers) has one row per layer, evaluated in its
// layer_K folder, and metrics.csv then a `layer` column after `case`. A case whose state and
// settings did not change is not evaluated again. Multi-layer rows also get effective_thickness,
// deposited_thickness and layer_relative_density, from consecutive layers (bed_thickness.hpp). The verify loop's characterise
// (`verify: {rounds: N}`) also measures the verify runs the loop added to the manifest
// (`verify_cases`) of the rounds before it, so that the model is refitted with them; run alone
// (`--only characterise`), all of them, as the loop's last characterise did.
// Replicated points (simulate: replicates) get one row per point in metrics.csv (each metric's
// mean, its _std over the replicates, and `replicates`); every run's own row is kept in
// metrics_replicates.csv.
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "analysis/replicate_summary.hpp"
#include "analysis/table.hpp"
#include "core/error.hpp"
#include "core/files.hpp"
#include "workflow/characterise/bed_thickness.hpp"
#include "workflow/characterise/case_metrics.hpp"
#include "workflow/spreading/substrate_roughness.hpp"
#include "workflow/cases/case_runner.hpp"
#include "workflow/spreading/case_setup.hpp"
#include "workflow/spreading/layer_feed.hpp"
#include "workflow/spreading/machine_layout.hpp"
#include "workflow/stage/stage.hpp"
#include "workflow/run/run_dir.hpp"
#include "workflow/spreading/scene_model.hpp"

namespace spreadmap {
namespace {

// The hash of the state a row measures, as its record (case.json, or layer.json of a layer) keeps it;
// "" for a record written before states were fingerprinted.
std::string state_fingerprint(const fs::path &case_dir, int layer) {
  const fs::path record = layer ? case_dir / layer_folder(layer) / "layer.json" : case_dir / "case.json";
  try {
    return nlohmann::json::parse(read_text(record)).value("state_hash", "");
  } catch (const std::exception &) {
    return "";
  }
}

class CharacteriseStage : public Stage {
 public:
  explicit CharacteriseStage(std::size_t verify_rounds) : verify_rounds_(verify_rounds) {}

  void validate(const Workflow &wf, const StageEntry &entry, const Scene *scene, PluginRegistry &registry,
                Diagnostics &diag) override {
    settings_ = read_characterise_settings(wf, entry.config, scene, registry, diag);
  }

  void run(StageContext &ctx) override {
    figures::use_style(settings_.style);
    const nlohmann::json manifest = ctx.run.manifest();
    if (!manifest.contains("cases") || manifest["cases"].empty())
      throw InputError("characterise: " + ctx.run.root().string() +
                       " has no simulated cases; run the simulate stage first (spreadmap run " + ctx.wf.file.string() +
                       ")");
    const std::string settings = settings_hash(settings_);
    std::vector<std::string> inputs;
    for (const auto &v : manifest["design"].value("variables", nlohmann::json::array())) inputs.push_back(v["name"]);

    std::vector<nlohmann::json> results;
    std::size_t evaluated = 0, missing = 0;
    nlohmann::json cases = manifest["cases"];
    const nlohmann::json verify_cases = manifest.value("verify_cases", nlohmann::json::array());
    // Run alone (--only without verify), the stage measures what the verify loop's last characterise
    // did: every round's runs that joined the training data (those the manifest records); in a whole
    // run the loop replays its rounds after this stage.
    std::size_t rounds = verify_rounds_;
    if (rounds == 0 && !ctx.options.only.empty() && !ctx.options.only.count("verify"))
      for (const auto &c : verify_cases) rounds = std::max<std::size_t>(rounds, c.value("round", std::size_t(0)) + 1);
    for (const auto &c : verify_cases)
      if (c.value("round", rounds) < rounds) cases.push_back(c);
    for (const auto &c : cases) {
      const std::string id = c["id"];
      const fs::path dir = c.contains("dir") ? ctx.run.root() / c["dir"].get<std::string>() : ctx.run.case_dir(id);
      if (!case_done(dir, c.value("hash", ""))) {
        ++missing;
        continue;
      }
      // one row per layer of a multi-layer case (layer 0: a single pass, as its own folder holds it)
      const Scene scene = read_scene_file(dir / "scene.json");
      const int layers = layered(scene) ? static_cast<int>(scene.layers.count) : 0;
      const std::size_t first = results.size();
      for (int layer = layers ? 1 : 0; layer <= layers; ++layer) {
        // the key rests on the measured state's own hash, so a state simulated again (after a heap or
        // a checkpoint was found damaged, say) is measured again, never described by old metrics
        const std::string key = stable_hash(settings + c.value("hash", "") + state_fingerprint(dir, layer) +
                                            (layer ? "/layer " + std::to_string(layer) : ""));
        bool now = false;
        nlohmann::json doc = case_metrics(ctx.registry, settings_, dir, id, key, ctx.options.force, now, layer);
        evaluated += now;
        doc["inputs"] = c["inputs"];
        if (c.contains("point")) doc["point"] = c["point"], doc["replicate"] = c["replicate"];
        results.push_back(doc);
      }
      if (layers) add_layer_thicknesses(ctx, scene, dir, results.begin() + static_cast<std::ptrdiff_t>(first));
    }
    if (missing)
      spdlog::warn("characterise: {} of {} cases have no finished state; run the simulate stage to complete them",
                   missing, cases.size());
    write_table(ctx, inputs, manifest, results);
    spdlog::info("characterise: {} cases in metrics.csv ({} evaluated, {} up to date)", results.size(), evaluated,
                 results.size() - evaluated);
  }

 private:
  // effective_thickness, deposited_thickness and layer_relative_density of each layer of one multi-layer
  // case (bed_thickness.hpp),
  // from its layer rows starting at `rows`; metrics.csv only (each layer's metrics.json stays its own).
  static void add_layer_thicknesses(StageContext &ctx, const Scene &scene, const fs::path &dir,
                                    std::vector<nlohmann::json>::iterator rows) {
    const auto number = [](const nlohmann::json &m, const char *key) {
      const auto &v = m.value(key, nlohmann::json());
      return v.is_number() ? v.get<double>() : std::nan("");
    };
    const int layers = static_cast<int>(scene.layers.count);
    std::vector<LayerBed> beds;
    const double level = substrate_level(scene);  // heights are measured from it (0: the flat plate)
    for (int k = 1; k <= layers; ++k) {
      const auto &m = rows[k - 1]["metrics"];
      const double gap = describe_spreader(layer_scene(scene, k), ctx.registry, dir / "scene.json").gap;
      // a machine's bed is measured from its platform, which dropped k x thickness below the plates
      const double edge = scene.machine ? machine_layout(scene).edge_above_platform(gap, k) : gap - level;
      beds.push_back({edge, number(m, "mean_height"), number(m, "solid_thickness")});
    }
    const auto thickness = layer_thicknesses(beds);
    for (int k = 1; k <= layers; ++k) {
      auto &row = rows[k - 1];
      const auto value = [](double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(); };
      row["metrics"]["effective_thickness"] = value(thickness[k - 1].effective);
      row["metrics"]["deposited_thickness"] = value(thickness[k - 1].deposited);
      row["metrics"]["layer_relative_density"] = value(thickness[k - 1].relative_density);
      row["units"]["effective_thickness"] = row["units"]["deposited_thickness"] = "m";
      row["units"]["layer_relative_density"] = "-";
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
    const bool replicated =
        std::any_of(results.begin(), results.end(), [](const auto &r) { return r.contains("point"); });
    if (!replicated) {
      table.write_csv(ctx.run.metrics_csv().string());
      write_atomic(ctx.run.root() / "metrics.units.json", units.dump(2) + "\n");
      return;
    }
    // every run's row, with its point and replicate; metrics.csv summarises them per point
    std::vector<std::string> point, replicate;
    for (const auto &r : results)
      point.push_back(r.value("point", r["case"].get<std::string>())),
          replicate.push_back(std::to_string(r.value("replicate", 0)));
    table.add_column("point", point);
    table.add_column("replicate", replicate);
    nlohmann::json run_units = units;
    run_units["point"] = "", run_units["replicate"] = "";
    table.write_csv((ctx.run.root() / "metrics_replicates.csv").string());
    write_atomic(ctx.run.root() / "metrics_replicates.units.json", run_units.dump(2) + "\n");
    for (const auto &m : present)
      if (units.contains(m)) units[analysis::std_column(m)] = units[m];
    units[analysis::replicates_column()] = "";
    analysis::summarise_replicates(table, "point", inputs, present, "metrics.csv")
        .write_csv(ctx.run.metrics_csv().string());
    write_atomic(ctx.run.root() / "metrics.units.json", units.dump(2) + "\n");
  }

  CharacteriseSettings settings_;
  std::size_t verify_rounds_ = 0;  // the verify loop's rounds whose runs are measured too
};

}  // namespace

std::unique_ptr<Stage> make_characterise_stage(std::size_t verify_rounds) {
  return std::make_unique<CharacteriseStage>(verify_rounds);
}

}  // namespace spreadmap
