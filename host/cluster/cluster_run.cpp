#include "cluster/cluster_run.hpp"

#include "cluster/slurm_executor.hpp"
#include "core/error.hpp"

namespace spreadmap::cluster {

int run_on_mpi(const std::filesystem::path &workflow, RunOptions options, const ClusterOptions &cluster,
               PluginRegistry &registry);  // mpi_run.cpp, or mpi_missing.cpp

std::vector<std::string> executor_names() { return {"local", "mpi", "slurm"}; }

int run_distributed(const std::filesystem::path &workflow, RunOptions options, const ClusterOptions &cluster,
                    PluginRegistry &registry) {
  if (cluster.executor == "mpi") return run_on_mpi(workflow, options, cluster, registry);
  if (cluster.executor == "slurm") {
    SlurmExecutor slurm(cluster.dry_run, cluster.threads_per_rank);
    options.executor = &slurm;
    return run_workflow(workflow, options, registry);
  }
  return run_workflow(workflow, options, registry);
}

}  // namespace spreadmap::cluster
