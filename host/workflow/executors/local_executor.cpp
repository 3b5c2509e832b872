#include "workflow/executors/local_executor.hpp"

#include <algorithm>
#include <atomic>
#include <mutex>
#include <optional>
#include <thread>

#include <spdlog/spdlog.h>

#include "core/error.hpp"
#include "core/stop.hpp"
#include "workflow/run/progress.hpp"
#include "workflow/stage/stage.hpp"
#include "workflow/run/run_dir.hpp"
#include "workflow/spreading/scene_model.hpp"

namespace spreadmap {

LocalExecutor::LocalExecutor(int jobs, int threads_per_case, RunJob run)
    : jobs_(std::max(0, jobs)), threads_per_case_(threads_per_case), run_(std::move(run)) {}

int LocalExecutor::cases_at_once(int jobs, cuda::Backend backend, std::size_t cases, unsigned cores) {
  const std::size_t wanted = jobs > 0 ? std::size_t(jobs) : backend == cuda::Backend::cuda ? std::max(1u, cores) : 1;
  return int(std::max<std::size_t>(1, std::min(wanted, cases)));
}

int LocalExecutor::threads_for(const Scene &scene, int running) const {
  if (threads_per_case_ > 0) return threads_per_case_;
  if (scene.threads > 0) return static_cast<int>(scene.threads);
  const int cores = std::max(1u, std::thread::hardware_concurrency());
  return std::max(1, cores / std::max(1, running));
}

void LocalExecutor::run_cases(CaseBatch &batch, StageContext &ctx) {
  if (batch.jobs.empty()) return;
  Progress progress(batch.label, batch.jobs.size(), ctx.options.quiet);
  std::string note;
  const cuda::Backend backend =
      jobs_ > 0 ? cuda::Backend::cpu : cuda::choose_backend(batch.jobs.front().request.scene.backend, note);
  const int pool = cases_at_once(jobs_, backend, batch.jobs.size(), std::thread::hardware_concurrency());
  if (jobs_ == 0 && pool > 1)
    spdlog::info("{} cases at once on the GPU, each on its own stream (--jobs sets another number)", pool);
  std::atomic<std::size_t> next{0};
  std::atomic<int> running{0};
  std::mutex failure_mutex;
  std::optional<CaseOutcome> failure;  // the first; the others are logged as they come
  auto failed = [&] {
    std::lock_guard<std::mutex> g(failure_mutex);
    return failure.has_value();
  };
  auto worker = [&] {
    while (!failed() && !stop_requested()) {
      const std::size_t k = next++;
      if (k >= batch.jobs.size()) return;
      CaseJob &job = batch.jobs[k];
      job.request.threads = threads_for(job.request.scene, pool);
      job.request.progress = [&progress, k, id = job.request.id](double f, const std::string &d) {
        progress.update(k, f, id + " " + d);
      };
      ++running;
      CaseOutcome o;
      try {
        o = run_(job, ctx.registry);
        if (o.ok && ctx.options.records_manifest()) record_outcome(ctx.run, o);
      } catch (const std::exception &e) {  // not the case itself: e.g. its record, on a full disk
        o.id = job.request.id;
        set_failure(o, e);
      }
      --running;
      if (o.ok) {
        progress.done_item();
        log_done(o);
        continue;
      }
      std::lock_guard<std::mutex> g(failure_mutex);
      if (failure || running > 0) log_failure(o, "");
      if (!failure) failure = o;  // thrown once the running cases are in
    }
  };
  std::vector<std::thread> threads;
  for (int j = 1; j < pool; ++j) threads.emplace_back(worker);
  worker();
  for (auto &t : threads) t.join();
  progress.finish();
  if (failure) throw_outcome(*failure, "");
  if (stop_requested()) throw Interrupted("interrupted: finished cases are kept; run the same command again to resume");
}

}  // namespace spreadmap
