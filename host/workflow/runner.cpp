#include <spdlog/spdlog.h>

#include <chrono>
#include <nlohmann/json.hpp>

#include "workflow/runner.hpp"
#include "core/error.hpp"
#include "core/files.hpp"
#include "core/suggest.hpp"
#include "workflow/executors/executor_hook.hpp"
#include "workflow/executors/local_executor.hpp"
#include "workflow/report/run_report.hpp"
#include "workflow/run/run_lock.hpp"
#include "workflow/spreading/scene_section.hpp"
#include "workflow/stage/stage.hpp"
#include "workflow/run/run_dir.hpp"
#include "workflow/spreading/scene_model.hpp"
#include "workflow/stage_table.hpp"

namespace spreadmap {

// report.html after every stage: a view of the run's files, never a result, so a failure to write it
// is said and the run goes on.
static void refresh_report(const fs::path &run) {
  try {
    write_run_report(run);
  } catch (const std::exception &e) {
    spdlog::warn("report: {} not written ({})", (run / "report.html").string(), e.what());
  }
}

static bool needs_scene(const Workflow &wf) {
  for (const auto &s : wf.stages)
    if (find_stage(s.kind)->needs_scene) return true;
  return false;
}

Validated validate_workflow(const fs::path &file, PluginRegistry &registry) {
  Validated v{load_workflow(file, stage_names()), {}, {}};
  Diagnostics diag;
  if (needs_scene(v.wf) || v.wf.root["scene"]) v.scene = resolve_scene(v.wf, registry, diag);
  for (auto &entry : v.wf.stages) {
    const StageInfo &info = *find_stage(entry.kind);  // load_workflow refused any other
    entry.settings = check_stage_settings(info, entry.config, v.wf.file.string(), diag);
    auto stage = info.make();
    stage->validate(v.wf, entry, v.scene ? &*v.scene : nullptr, registry, diag);
    v.stages.push_back(std::move(stage));
  }
  diag.throw_if_any();
  return v;
}

int run_workflow(const fs::path &file, const RunOptions &given, PluginRegistry &registry) {
  RunOptions options = given;
  LocalExecutor local(options.jobs, options.case_threads);
  if (!options.executor) options.executor = &local;
  Validated v = validate_workflow(file, registry);
  for (const auto &only : options.only) {
    bool found = false;
    for (const auto &s : v.wf.stages) found |= iequals(s.kind, only);
    if (!found)
      throw InputError("--only " + only + ": this workflow has no such stage (stages: " + [&] {
        std::vector<std::string> k;
        for (auto &s : v.wf.stages) k.push_back(s.kind);
        return join(k);
      }() + ")");
  }
  const fs::path root = options.out.empty() ? fs::path("runs") / v.wf.name : options.out;
  // One writer per run directory, held to the end; one case of a Slurm array leaves the manifest
  // alone, so its sibling tasks may hold the lock beside it.
  const RunLock lock(root, options.records_manifest() ? RunLock::Mode::exclusive : RunLock::Mode::shared);
  RunDirectory run(root);
  if (options.records_manifest())
    run.update_manifest([&](nlohmann::json &m) {
      m["workflow"] = {{"file", fs::absolute(file).string()}, {"name", v.wf.name}};
      m["scene"] = v.scene ? to_json(*v.scene) : nlohmann::json();
    });
  spdlog::info("run directory: {}", run.root().string());
  if (options.records_manifest())
    if (const auto n = remove_stale_temporaries(run.root()))
      spdlog::info("removed {} temporary files of writes a killed run left unfinished", n);
  Scene scene = v.scene ? *v.scene : Scene{};  // a workflow without a scene has no stage that reads one
  StageContext ctx{v.wf, scene, run, registry, options};
  for (std::size_t i = 0; i < v.stages.size(); ++i) {
    const std::string kind = v.wf.stages[i].kind;
    bool selected = options.only.empty();
    for (const auto &o : options.only) selected |= iequals(o, kind);
    if (!selected) {
      v.stages[i]->adjust_scene(scene, run);
      continue;
    }
    if (kind != "simulate") options.executor->release();  // the later stages run here alone
    spdlog::info("stage {}: {}", i + 1, kind);
    const auto t0 = std::chrono::steady_clock::now();
    const std::string start = RunDirectory::now_iso();
    v.stages[i]->run(ctx);
    v.stages[i]->adjust_scene(scene, run);
    if (!options.executor->runs_later_stages()) break;  // they wait for the cases in a job
    if (!options.records_manifest()) continue;
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    run.update_manifest([&](nlohmann::json &m) {
      m["stages"][kind] = {{"start", start}, {"end", RunDirectory::now_iso()}, {"wall_seconds", wall}};
    });
    refresh_report(run.root());
  }
  if (options.records_manifest() && fs::exists(run.root() / "report.html"))
    spdlog::info("report: {}", (run.root() / "report.html").string());
  return exit_ok;
}

}  // namespace spreadmap
