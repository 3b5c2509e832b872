// `spreadmap run WORKFLOW --executor mpi|slurm`: the same workflow, its simulate stage's cases run
// on MPI ranks or as Slurm array tasks. The local executor is run_workflow's default.
#pragma once
#include <filesystem>
#include <string>
#include <vector>

#include "workflow/runner.hpp"
#include "core/registry.hpp"
#include "workflow/stage/stage.hpp"
#include "workflow/spreading/scene_model.hpp"

namespace spreadmap::cluster {

struct ClusterOptions {
  std::string executor = "local";  // local | mpi | slurm
  bool dry_run = false;            // slurm: write the scripts, submit nothing
  int threads_per_rank = 0;        // OpenMP threads of each case; 0: scene.threads, else a share of the node
};

std::vector<std::string> executor_names();
bool mpi_available();  // this build can run --executor mpi

int run_distributed(const std::filesystem::path &workflow, RunOptions options, const ClusterOptions &cluster,
                    PluginRegistry &registry);

}  // namespace spreadmap::cluster
