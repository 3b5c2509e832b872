// The default executor: the cases run here, in a pool of --jobs threads, each case with its share of
// the machine's cores. Cases that share a settled heap order themselves in heap_cache.cpp (one
// settles it, the others wait and reuse it), so the pool hands out cases in design order.
// A failed case stops the hand-out; the running cases finish and are recorded, then the first
// failure is thrown. After SIGINT/SIGTERM no case starts; the running ones save their checkpoints.
#pragma once
#include <functional>

#include "cuda/backend.hpp"
#include "workflow/executors/executor_hook.hpp"

namespace spreadmap {

class LocalExecutor : public CaseExecutor {
 public:
  // What runs one case; run_case_job, or a stand-in in tests. Called from several threads at once.
  using RunJob = std::function<CaseOutcome(const CaseJob &job, PluginRegistry &registry)>;

  // jobs: cases run at once; 0: cases_at_once's choice. threads_per_case: OpenMP threads of each
  // case; 0: scene.threads when set, else the machine's cores shared by the cases running at once.
  explicit LocalExecutor(int jobs, int threads_per_case = 0, RunJob run = run_case_job);
  void run_cases(CaseBatch &batch, StageContext &ctx) override;

  // The threads rule above, for `running` cases at once.
  int threads_for(const Scene &scene, int running) const;

  // How many of `cases` run at once when --jobs is not given (jobs 0): one on the CPU (it takes every
  // core through OpenMP); one per CPU core when the cases step on a GPU, where a case needs only a
  // host thread that launches its kernels and the device runs the cases' streams side by side.
  static int cases_at_once(int jobs, cuda::Backend backend, std::size_t cases, unsigned cores);

 private:
  int jobs_;
  int threads_per_case_;
  RunJob run_;
};

}  // namespace spreadmap
