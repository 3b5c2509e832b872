// --executor mpi in a build with MPI: every rank starts here; rank 0 runs the workflow, handing the
// cases out, and the others serve cases until it lets them go.
#include "workflow/runner.hpp"
#include "cluster/cluster_run.hpp"
#include "cluster/mpi_dispatcher.hpp"
#include "cluster/mpi_worker.hpp"

namespace spreadmap::cluster {

bool mpi_available() { return true; }

int run_on_mpi(const std::filesystem::path &workflow, RunOptions options, const ClusterOptions &cluster,
               PluginRegistry &registry) {
  MpiSession mpi;
  if (mpi.rank() > 0) return serve_cases(mpi, cluster.threads_per_rank, registry);
  MpiDispatcher dispatcher(mpi, cluster.threads_per_rank);
  options.executor = &dispatcher;
  try {
    const int rc = run_workflow(workflow, options, registry);
    dispatcher.release();
    return rc;
  } catch (...) {
    dispatcher.release();  // the workers exit before rank 0 reports the error
    throw;
  }
}

}  // namespace spreadmap::cluster
