// Rank 0 under `mpirun -n N spreadmap run WORKFLOW --executor mpi`: it keeps the manifest and hands
// the unfinished cases out one at a time to the worker ranks that ask (mpi_worker.hpp), so a rank
// that finishes early takes the next case and unequal case times balance. With N = 1 it runs the
// cases itself. After the simulate stage it lets the workers go and runs the later stages alone.
#pragma once
#include <set>

#include "cluster/mpi_session.hpp"
#include "workflow/executors/executor_hook.hpp"
#include "workflow/stage/stage.hpp"
#include "workflow/spreading/scene_model.hpp"

namespace spreadmap::cluster {

class MpiDispatcher : public CaseExecutor {
 public:
  // threads_per_rank: OpenMP threads of each case; 0: scene.threads, else the rank's share of its node.
  MpiDispatcher(MpiSession &mpi, int threads_per_rank) : mpi_(mpi), threads_(threads_per_rank) {}
  void run_cases(CaseBatch &batch, StageContext &ctx) override;
  // Tells every worker to exit (answering the request each sends when it is free) and ends MPI.
  void release() override;

 private:
  void run_alone(CaseBatch &batch, StageContext &ctx);
  void hand_out(CaseBatch &batch, StageContext &ctx);
  void stop_worker(int rank);

  MpiSession &mpi_;
  int threads_;
  std::set<int> waiting_;  // workers whose request for a case is not answered yet
  std::set<int> stopped_;
  bool released_ = false;
};

}  // namespace spreadmap::cluster
