// Cases with the same powder, domain, contacts and spreader position share one settled heap
// (workflow/cases/case_runner.hpp): the first of them settles it into heaps/, the others read it. Cases
// in different processes cannot share the in-process lock that orders this on one machine, so the
// executors order it themselves: a case whose heap another rank is settling waits for it, rather
// than settling the same heap again at the same time.
#pragma once
#include <string>
#include <vector>

#include "workflow/executors/executor_hook.hpp"

namespace spreadmap::cluster {

std::string heap_key(const CaseJob &job, PluginRegistry &registry);
// True once the case's settled heap is on disk (it is then only read).
bool heap_ready(const CaseJob &job, PluginRegistry &registry);

// The jobs split in two, design order kept: `first` holds one case for each heap that is not on
// disk yet (it settles it), `rest` the others (they can all run at once once `first` is done).
struct HeapOrder {
  std::vector<std::size_t> first, rest;  // design indices
};
HeapOrder order_by_heap(const std::vector<CaseJob> &jobs, PluginRegistry &registry);

}  // namespace spreadmap::cluster
