#include "cluster/mpi_dispatcher.hpp"

#include <spdlog/spdlog.h>

#include <chrono>
#include <map>
#include <thread>
#include <nlohmann/json.hpp>

#include "cluster/cpu_share.hpp"
#include "cluster/heap_order.hpp"
#include "core/error.hpp"
#include "core/stop.hpp"
#include "workflow/executors/local_executor.hpp"
#include "workflow/run/progress.hpp"

namespace spreadmap::cluster {
namespace {

std::string on_rank(const CaseOutcome &o) { return " on rank " + std::to_string(o.rank) + " (" + o.host + ")"; }

}  // namespace

void MpiDispatcher::run_cases(CaseBatch &batch, StageContext &ctx) {
  if (released_) throw RunFailure("MPI: the workers were already released before the simulate stage");
  if (batch.jobs.empty()) return;
  if (mpi_.size() == 1) return run_alone(batch, ctx);
  hand_out(batch, ctx);
}

// One rank: the cases one after another, here, with the rank's share of its node.
void MpiDispatcher::run_alone(CaseBatch &batch, StageContext &ctx) {
  LocalExecutor(1, rank_threads(ctx.scene, threads_, mpi_.computing_ranks_on_node())).run_cases(batch, ctx);
}

// Several ranks: answer each worker's request with the next case it may start. A case whose heap
// another rank is settling waits for it (heap_order.hpp); a worker with nothing to start waits too.
void MpiDispatcher::hand_out(CaseBatch &batch, StageContext &ctx) {
  Progress progress("simulate", batch.jobs.size(), ctx.options.quiet);
  std::vector<std::size_t> pending;  // positions in batch.jobs, design order
  for (std::size_t k = 0; k < batch.jobs.size(); ++k) pending.push_back(k);
  std::map<int, std::size_t> running;  // worker -> position in batch.jobs
  std::set<std::string> settling;      // heaps a running case is making
  std::optional<CaseOutcome> failure;
  bool stopping = false;
  spdlog::info("simulate: {} cases for {} worker ranks", batch.jobs.size(), mpi_.size() - 1);

  auto next_for_worker = [&]() -> std::optional<std::size_t> {
    for (auto it = pending.begin(); it != pending.end(); ++it) {
      const CaseJob &job = batch.jobs[*it];
      const std::string key = heap_key(job, ctx.registry);
      if (settling.count(key) && !heap_ready(job, ctx.registry)) continue;
      if (!heap_ready(job, ctx.registry)) settling.insert(key);
      const std::size_t k = *it;
      pending.erase(it);
      return k;
    }
    return std::nullopt;
  };

  for (;;) {
    stopping = stopping || failure.has_value() || stop_requested();
    for (auto it = waiting_.begin(); it != waiting_.end();) {
      const int worker = *it;
      if (stopping || pending.empty()) {
        stop_worker(worker);  // nothing more for it in this run
        it = waiting_.erase(it);
        continue;
      }
      const auto k = next_for_worker();
      if (!k) {
        ++it;
        continue;
      }
      CaseJob &job = batch.jobs[*k];
      mpi_.send(worker, tag_work, job_to_json(job).dump());
      running[worker] = *k;
      progress.update(*k, 0.0, job.request.id + " on rank " + std::to_string(worker));
      it = waiting_.erase(it);
    }
    if (running.empty() && (pending.empty() || stopping)) break;

    const auto message = mpi_.poll(-1, tag_ask);
    if (!message) {
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
      continue;
    }
    waiting_.insert(message->source);
    if (message->text.empty()) continue;  // a worker's first request
    const CaseOutcome o = outcome_from_json(nlohmann::json::parse(message->text));
    const auto r = running.find(message->source);
    if (r == running.end()) continue;
    settling.erase(heap_key(batch.jobs[r->second], ctx.registry));
    running.erase(r);
    if (!o.ok) {
      if (failure || !running.empty()) log_failure(o, on_rank(o));
      if (!failure) failure = o;  // thrown once the running cases are in
      continue;
    }
    record_outcome(ctx.run, o);
    progress.done_item();
    log_done(o, on_rank(o));
  }
  progress.finish();
  if (failure) throw_outcome(*failure, on_rank(*failure));
  if (stop_requested()) throw Interrupted("interrupted: finished cases are kept; run the same command again to resume");
}

void MpiDispatcher::stop_worker(int rank) {
  mpi_.send(rank, tag_stop, "");
  stopped_.insert(rank);
}

void MpiDispatcher::release() {
  if (released_) return;
  released_ = true;
  // Every worker asks for a case as soon as it starts and after each case: answer each one's
  // request with "stop". None is running a case here (hand_out waits for them all).
  for (const int w : waiting_) stop_worker(w);
  waiting_.clear();
  while (static_cast<int>(stopped_.size()) < mpi_.size() - 1) {
    const MpiMessage m = mpi_.wait(-1, tag_ask);
    if (!stopped_.count(m.source)) stop_worker(m.source);
  }
  mpi_.finish();
}

}  // namespace spreadmap::cluster
