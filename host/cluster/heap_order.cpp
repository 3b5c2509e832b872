#include "cluster/heap_order.hpp"

#include <filesystem>
#include <set>

namespace spreadmap::cluster {

std::string heap_key(const CaseJob &job, PluginRegistry &registry) { return heap_hash(job.request.scene, registry); }

// The file name workflow/cases/heap_cache.cpp gives a settled heap. Were it ever to change, a case would only
// wait for its heap's first case needlessly; nothing would be computed wrongly.
bool heap_ready(const CaseJob &job, PluginRegistry &registry) {
  std::error_code ec;
  return std::filesystem::exists(job.request.heaps / ("heap_" + heap_key(job, registry) + ".vtp"), ec);
}

HeapOrder order_by_heap(const std::vector<CaseJob> &jobs, PluginRegistry &registry) {
  HeapOrder order;
  std::set<std::string> settling;
  for (const auto &job : jobs) {
    if (!heap_ready(job, registry) && settling.insert(heap_key(job, registry)).second) order.first.push_back(job.index);
    else order.rest.push_back(job.index);
  }
  return order;
}

}  // namespace spreadmap::cluster
