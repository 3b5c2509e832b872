// --executor mpi in a build without MPI: a clear refusal.
#include "cluster/cluster_run.hpp"
#include "core/error.hpp"

namespace spreadmap::cluster {

bool mpi_available() { return false; }

int run_on_mpi(const std::filesystem::path &, RunOptions, const ClusterOptions &, PluginRegistry &) {
  throw InputError(
      "--executor mpi: this spreadmap was built without MPI. Install an MPI (Debian: apt-get "
      "install libopenmpi-dev openmpi-bin), configure the build again and rebuild; or use --executor "
      "slurm, or the local executor (--jobs N)");
}

}  // namespace spreadmap::cluster
