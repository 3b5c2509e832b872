// A worker rank (rank > 0) under `mpirun ... --executor mpi`: it asks rank 0 for a case, runs it,
// reports how it went with its next request, and exits 0 when rank 0 says stop. It never reads the
// workflow or touches manifest.json: the case arrives complete from rank 0, and writes only its
// own folder (and the shared settled heap that rank 0 told it to make).
#pragma once
#include "cluster/mpi_session.hpp"
#include "core/registry.hpp"

namespace spreadmap::cluster {

// threads_per_rank: as MpiDispatcher's.
int serve_cases(MpiSession &mpi, int threads_per_rank, PluginRegistry &registry);

}  // namespace spreadmap::cluster
