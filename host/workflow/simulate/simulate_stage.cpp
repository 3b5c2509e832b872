// simulate: hands every unfinished case of the design to the run's executor (here in --jobs threads,
// on MPI ranks or as Slurm tasks), each resumable; a finished case whose inputs did not change is
// never recomputed. With `replicates: N` each design point runs N times with independent heaps
// (simulate/replicates.hpp): the runs are numbered point by point (point i, replicate r: i * N + r).
#include <spdlog/spdlog.h>
#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "core/files.hpp"
#include "core/schema.hpp"
#include "cuda/backend.hpp"
#include "workflow/simulate/adaptive_run.hpp"
#include "workflow/spreading/coarse_grain.hpp"
#include "workflow/simulate/design.hpp"
#include "workflow/cases/replicates.hpp"
#include "workflow/executors/executor_hook.hpp"
#include "workflow/figures/figure_style.hpp"
#include "workflow/figures/stage_figures.hpp"
#include "workflow/stage/stage.hpp"
#include "workflow/run/run_dir.hpp"
#include "workflow/spreading/scene_model.hpp"
#include "workflow/stage/stage_settings.hpp"

namespace spreadmap {
namespace {

// A finished case whose outcome the manifest never recorded (the run was killed between the case's
// files and its record): its timing from the case's own timing.json, when that was written.
void recover_timing(nlohmann::json &c, const fs::path &dir) {
  try {
    const auto t = nlohmann::json::parse(read_text(dir / "timing.json"));
    for (const char *k : {"start", "end", "wall_seconds", "host"})
      if (t.contains(k)) c[k] = t[k];
  } catch (const std::exception &) {
    // no timing.json (a case of an older version): the manifest says only that it is done
  }
}

constexpr sm_param_v1 simulate_schema[] = {
    table("design", "the settings to simulate: type full_factorial, list, latin_hypercube or adaptive, and the "
                    "variables' values (docs/workflows.md)"),
    integer("replicates", 1, max_replicates, 1, "runs of each design point, each with its own heap"),
    table("render", "true, false or the figure's settings {width: 1920, vector: pdf, frames: true}"),
};

class SimulateStage : public Stage {
 public:
  void validate(const Workflow &wf, const StageEntry &entry, const Scene *scene, PluginRegistry &registry,
                Diagnostics &diag) override {
    const std::string file = wf.file.string();
    style_ = figures::read_style(entry.config["render"], true, true, file, "simulate.render", diag);
    render_ = style_.on;
    replicates_ = setting_count(entry.settings, "replicates");
    if (!scene) return;  // scene errors already reported
    design_ = parse_design(entry.config["design"], file, "simulate.design", *scene, registry, diag);
    if (design_.type == "adaptive" && replicates_ > 1)
      diag.error(Location::of(file, entry.config["replicates"]), "simulate.replicates",
                 "an adaptive design runs one heap per case",
                 "remove replicates, or use a full_factorial or list design");
    if (layered(*scene) && design_.type == "adaptive")
      diag.error(Location::of(file, entry.config["design"]), "simulate.design",
                 "an adaptive design measures one pass; a multi-layer scene is not supported yet",
                 "use a full_factorial or list design, or spread one layer on a plate (scene.layers.count: 1, no "
                 "scene.machine)");
    if (layered(*scene) && replicates_ > 1)
      diag.error(Location::of(file, entry.config["replicates"]), "simulate.replicates",
                 "replicates of a multi-layer scene are not supported yet",
                 "remove replicates, or spread one layer on a plate (scene.layers.count: 1, no scene.machine)");
  }

  void run(StageContext &ctx) override {
    figures::use_style(style_);
    if (design_.type == "adaptive") return run_adaptive_design(ctx, design_, render_);
    const std::size_t n = design_.cases.size() * replicates_;
    const auto &only_case = ctx.options.only_case;
    if (only_case && *only_case >= n)
      throw InputError("--case " + std::to_string(*only_case) + ": the design has " + std::to_string(n) +
                       " cases, numbered 0 to " + std::to_string(n - 1));
    CaseBatch batch{{}, n};  // the unfinished cases
    nlohmann::json cases = nlohmann::json::array();
    for (std::size_t i = 0; i < n; ++i) {
      if (only_case && i != *only_case) continue;
      const std::size_t point = i / replicates_, replicate = i % replicates_;
      CaseRequest req;
      req.id = replicate_id(RunDirectory::case_id(point), replicate);
      req.scene = replicate_scene(case_scene(ctx.scene, design_, point), replicate);
      req.inputs = case_inputs(design_, point);
      req.dir = ctx.run.case_dir(req.id);
      req.heaps = ctx.run.heaps();
      const std::string hash = case_hash(req.scene);
      cases.push_back({{"id", req.id}, {"inputs", req.inputs}, {"hash", hash}});
      if (replicates_ > 1) cases.back()["point"] = RunDirectory::case_id(point), cases.back()["replicate"] = replicate;
      if (!ctx.options.force && case_finished(req.dir, hash)) {
        if (render_) redraw_missing_snapshot(req);
        continue;
      }
      if (ctx.options.force) {
        std::error_code ec;
        fs::remove(req.dir / "checkpoint.bin", ec);
      }
      write_scene_file(req.dir / "scene.json", coarse_grained(req.scene, ctx.registry));  // as the engine runs it
      batch.jobs.push_back({i, std::move(req), render_});
    }
    if (ctx.options.records_manifest())
      ctx.run.update_manifest([&](nlohmann::json &m) {
        nlohmann::json old = m.value("cases", nlohmann::json::array());
        for (auto &c : cases)
          for (const auto &o : old)
            if (o.value("id", "") == c["id"] && o.value("hash", "") == c["hash"])
              for (const char *k : {"start", "end", "wall_seconds", "status", "rank", "host"})
                if (o.contains(k)) c[k] = o[k];
        // Finished where no record says so: by a Slurm array task (they leave the manifest alone), or
        // on an MPI rank killed before rank 0 heard of it. case.json is the proof.
        for (auto &c : cases)
          if (!c.contains("status") &&
              case_finished(ctx.run.case_dir(c["id"].get<std::string>()), c["hash"].get<std::string>())) {
            c["status"] = "done";
            recover_timing(c, ctx.run.case_dir(c["id"].get<std::string>()));
          }
        m["cases"] = cases;
        m["design"] = {{"type", design_.type}, {"variables", [&] {
                                                  auto v = nlohmann::json::array();
                                                  for (const auto &d : design_.variables)
                                                    v.push_back({{"name", d.key.name}, {"unit", d.key.param->unit}});
                                                  return v;
                                                }()}};
        if (replicates_ > 1) m["design"]["replicates"] = replicates_;
        m["plugins"]["contact/" + ctx.scene.contact.use] =
            ctx.registry.get("contact", ctx.scene.contact.use).descriptor->version;
        m["plugins"]["spreader/" + ctx.scene.spreader.use] =
            ctx.registry.get("spreader", ctx.scene.spreader.use).descriptor->version;
      });
    if (only_case)
      spdlog::info("simulate: case {} of {}: {}", RunDirectory::case_id(*only_case), n,
                   batch.jobs.empty() ? "finished already" : "to run");
    else
      spdlog::info(
          "simulate: {} cases{}, {} to run, {} finished already", n,
          replicates_ > 1 ? fmt::format(" ({} points x {} replicates)", design_.cases.size(), replicates_) : "",
          batch.jobs.size(), n - batch.jobs.size());
    std::string backend_note;  // throws InputError for `cuda` with no usable device, before any case runs
    cuda::choose_backend(ctx.scene.backend, backend_note);
    ctx.options.executor->run_cases(batch, ctx);
  }

 private:
  Design design_;
  std::size_t replicates_ = 1;
  figures::Style style_;
  bool render_ = true;
};

}  // namespace

std::unique_ptr<Stage> make_simulate_stage() { return std::make_unique<SimulateStage>(); }
SchemaView simulate_settings() { return {simulate_schema, std::size(simulate_schema)}; }

}  // namespace spreadmap
