#include "cluster/mpi_worker.hpp"

#include <spdlog/spdlog.h>
#include <nlohmann/json.hpp>

#include "cluster/cpu_share.hpp"
#include "workflow/executors/executor_hook.hpp"

namespace spreadmap::cluster {

int serve_cases(MpiSession &mpi, int threads_per_rank, PluginRegistry &registry) {
  // Many ranks write to one terminal: say which one speaks.
  spdlog::set_pattern("%^%l%$: [rank " + std::to_string(mpi.rank()) + "] %v");
  std::string report;  // the outcome of the last case, sent with the next request
  for (;;) {
    mpi.send(0, tag_ask, report);
    const MpiMessage m = mpi.wait(0, -1);
    if (m.tag == tag_stop) break;
    CaseJob job = job_from_json(nlohmann::json::parse(m.text));
    job.request.threads = rank_threads(job.request.scene, threads_per_rank, mpi.computing_ranks_on_node());
    spdlog::debug("{}: {} OpenMP threads", job.request.id, job.request.threads);
    CaseOutcome o = run_case_job(job, registry);
    o.rank = mpi.rank();
    report = outcome_to_json(o).dump();
  }
  mpi.finish();
  return 0;
}

}  // namespace spreadmap::cluster
