#include "cluster/cpu_share.hpp"

#include <sched.h>
#include <unistd.h>

#include <algorithm>

namespace spreadmap::cluster {

int default_threads_per_rank(int ranks_on_node) {
  cpu_set_t set;
  CPU_ZERO(&set);
  const long online = ::sysconf(_SC_NPROCESSORS_ONLN);
  if (::sched_getaffinity(0, sizeof set, &set) != 0) return std::max(1L, online / std::max(1, ranks_on_node));
  const int mine = CPU_COUNT(&set);
  if (mine < online) return std::max(1, mine);
  return std::max(1, mine / std::max(1, ranks_on_node));
}

int rank_threads(const Scene &scene, int requested, int ranks_on_node) {
  if (requested > 0) return requested;
  if (scene.threads > 0) return static_cast<int>(scene.threads);
  return default_threads_per_rank(ranks_on_node);
}

}  // namespace spreadmap::cluster
