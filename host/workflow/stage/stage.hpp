// A stage reads only the files of the stage before it (in the run directory) and writes its own,
// so each can be re-run, swapped or run alone (`--only train`). validate() checks its settings
// before any stage runs; run() does the work.
#pragma once
#include <memory>
#include <optional>
#include <set>
#include <string>

#include "core/diagnostics.hpp"
#include "core/registry.hpp"
#include "workflow/file/workflow.hpp"

namespace spreadmap {

class CaseExecutor;
class RunDirectory;
struct Scene;

struct RunOptions {
  bool force = false;
  bool quiet = false;
  int jobs = 0;                // cases run at once; 0: LocalExecutor::cases_at_once chooses
  std::set<std::string> only;  // empty = all stages
  fs::path out;                // run directory; empty = runs/<name>
  // Where the simulate stage's cases run (workflow/executors/executor_hook.hpp); null: here, in `jobs` threads
  // (run_workflow gives the stages a LocalExecutor).
  CaseExecutor *executor = nullptr;
  // --case N: this one case of the design only, as a Slurm array task runs it. Many such processes
  // run at once, so none of them writes manifest.json (the job of the later stages does).
  std::optional<std::size_t> only_case;
  int case_threads = 0;  // OpenMP threads of each case run here; 0: scene.threads, else all the cores
  bool records_manifest() const { return !only_case; }
};

struct StageContext {
  const Workflow &wf;
  const Scene &scene;  // resolved (SI)
  RunDirectory &run;
  PluginRegistry &registry;
  const RunOptions &options;
};

class Stage {
 public:
  virtual ~Stage() = default;
  // `scene`: null when the workflow has none or its problems left none to check against.
  virtual void validate(const Workflow &wf, const StageEntry &entry, const Scene *scene, PluginRegistry &registry,
                        Diagnostics &diag) = 0;
  virtual void run(StageContext &ctx) = 0;
  // Before the later stages run (whether this one ran now or before): what this stage's result
  // changes in the scene they see. Only calibrate changes it (its calibrated contact parameters).
  virtual void adjust_scene(Scene &, const RunDirectory &) {}
};

// The stages are the rows of stage_table() (workflow/stage_table.hpp). These three are also made by
// the verify loop, which refits the map with its runs: verify_rounds > 0 makes the loop's own
// characterise stage, which also measures the runs of its first rounds.
std::unique_ptr<Stage> make_characterise_stage(std::size_t verify_rounds = 0);
std::unique_ptr<Stage> make_train_stage();
std::unique_ptr<Stage> make_map_stage();

}  // namespace spreadmap
