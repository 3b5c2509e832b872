// calibrate: a calibration file (docs/calibration.md) run as a workflow stage, into calibrate/ of
// the run directory (its runs kept and reused like `spreadmap calibrate`'s). With apply: true the
// calibrated values (each parameter's best) replace those of the scene's particle-particle contact
// law for every later stage, so a workflow goes from measured angles to a process map of the
// calibrated powder:
//
//   - calibrate: {file: glass_beads.yaml, apply: true}
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <fstream>

#include "core/error.hpp"
#include "core/files.hpp"
#include "core/schema.hpp"
#include "workflow/calibrate/calibration.hpp"
#include "workflow/calibrate/calibration_file.hpp"
#include "workflow/stage/stage.hpp"
#include "workflow/run/run_dir.hpp"
#include "workflow/spreading/scene_model.hpp"
#include "workflow/stage/stage_settings.hpp"

#include <spreadmap/params.hpp>
#include <nlohmann/json.hpp>

namespace spreadmap {
namespace {
namespace sm = spreadmap;

constexpr sm_param_v1 calibrate_schema[] = {
    {"file", SM_STRING, "-", 0, 0, 0, nullptr, 1, nullptr,
     "the calibration file (docs/calibration.md), relative to the workflow, e.g. glass_beads.yaml"},
    sm::boolean("apply", false, "the later stages use the calibrated contact parameters (each one's best value)"),
};

class CalibrateStage : public Stage {
 public:
  void validate(const Workflow &wf, const StageEntry &entry, const Scene *scene, PluginRegistry &registry,
                Diagnostics &diag) override {
    const std::string file = wf.file.string();
    apply_ = setting_flag(entry.settings, "apply");
    const std::string name = setting_text(entry.settings, "file");
    if (name.empty()) {  // a missing key is reported by the settings' check
      if (entry.config["file"])
        diag.error(Location::of(file, entry.config["file"]), "calibrate.file", "is empty",
                   "name the calibration file: file: glass_beads.yaml (docs/calibration.md)");
      return;
    }
    try {
      calibration_ = calibrate::read_calibration_file(wf.resolve(name), registry);
    } catch (const InputError &e) {
      diag.error(Location::of(file, entry.config["file"]), "calibrate.file", "the calibration file has errors (below)");
      for (const auto &m : e.messages) diag.error(m);
      return;
    }
    for (const auto &t : calibration_.tests)
      if (!t.measured)
        diag.error(Location::of(file, entry.config["file"]), "calibrate.file",
                   fmt::format("its test {} has no measured angle", t.name),
                   "give it angle: and uncertainty: (a stage calibrates; `spreadmap calibrate --at` only simulates)");
    // calibrated values belong to the law that produced the angles
    if (apply_ && scene && scene->contact.use != calibration_.law)
      diag.error(Location::of(file, entry.config["apply"]), "calibrate.apply",
                 fmt::format("the scene's contact law is {}, the calibration's scenes use {}: the calibrated values "
                             "belong to that law",
                             scene->contact.use, calibration_.law),
                 "use the same contact law in the scene and in the calibration's scenes, or apply: false");
  }

  void run(StageContext &ctx) override {
    calibrate::run_calibration(calibration_, ctx.run.root() / "calibrate", ctx.registry);
  }

  void adjust_scene(Scene &scene, const RunDirectory &run) override {
    if (!apply_) return;
    const fs::path result = run.root() / "calibrate" / "calibration.json";
    if (!fs::exists(result))
      throw InputError(
          fmt::format("{}: the calibrate stage has not run yet ({} is missing), and apply: true "
                      "makes the later stages need it; run the workflow without --only, or --only calibrate",
                      calibration_.file.string(), result.string()));
    const auto j = nlohmann::json::parse(read_text(result));
    for (const auto &p : calibration_.parameters) {
      const double best = j.at("parameters").at(p.name).at("best");
      scene.contact.params[p.name] = best;
      spdlog::info("calibrate: the later stages use {} = {:.4g} (calibrated)", p.name, best);
    }
  }

 private:
  calibrate::CalibrationFile calibration_;
  bool apply_ = false;
};

}  // namespace

std::unique_ptr<Stage> make_calibrate_stage() { return std::make_unique<CalibrateStage>(); }
SchemaView calibrate_settings() { return {calibrate_schema, std::size(calibrate_schema)}; }

}  // namespace spreadmap
