// `spreadmap run WORKFLOW --executor slurm [--dry-run]`: the simulate stage's unfinished cases
// become Slurm job arrays and the later stages a job that waits for them (slurm_script.hpp). The
// scripts are written into <run>/slurm/; --dry-run prints the path of submit.sh and stops there,
// otherwise submit.sh runs (sbatch) and its job ids are printed. Nothing is computed here.
#pragma once
#include "workflow/executors/executor_hook.hpp"
#include "workflow/stage/stage.hpp"
#include "workflow/spreading/scene_model.hpp"

namespace spreadmap::cluster {

class SlurmExecutor : public CaseExecutor {
 public:
  // threads: --cpus-per-task of each case; 0: scene.threads when set, else 1.
  SlurmExecutor(bool dry_run, int threads) : dry_run_(dry_run), threads_(threads) {}
  void run_cases(CaseBatch &batch, StageContext &ctx) override;
  bool runs_later_stages() const override { return false; }
  // A stage other than simulate would run here, on the login node: refused.
  void release() override;

 private:
  bool dry_run_;
  int threads_;
};

}  // namespace spreadmap::cluster
