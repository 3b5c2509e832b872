// How many OpenMP threads a rank's case gets when --threads-per-rank is not given.
#pragma once
#include "workflow/spreading/scene_model.hpp"

namespace spreadmap::cluster {

// The CPUs this process may run on, shared by the `ranks_on_node` computing ranks of its node. A
// process that mpirun bound to fewer CPUs than the node has keeps its binding (it is already its
// share); an unbound one divides the node. At least 1.
int default_threads_per_rank(int ranks_on_node);

// The threads of one case on a rank: --threads-per-rank when given, else scene.threads when set,
// else the default above.
int rank_threads(const Scene &scene, int requested, int ranks_on_node);

}  // namespace spreadmap::cluster
