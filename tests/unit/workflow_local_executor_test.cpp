// The local executor's pool (workflow/executors/local_executor.hpp), with small stand-ins for the cases: each
// job runs exactly once on a pool of exactly --jobs threads; a failure stops the hand-out, the
// running cases finish and are recorded, and then the failure is thrown; a stop request leaves the
// unstarted cases unrun.
#include <gtest/gtest.h>
#include <spdlog/sinks/base_sink.h>
#include <spdlog/spdlog.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <thread>

#include "workflow/run/run_dir.hpp"
#include "core/error.hpp"
#include "core/stop.hpp"
#include "workflow/executors/local_executor.hpp"
#include "workflow/stage/stage.hpp"

namespace sm = spreadmap;
namespace fs = std::filesystem;

namespace {

// A run directory, its manifest listing the batch's cases as the simulate stage leaves it, and the
// context an executor is given.
struct PoolRun {
  explicit PoolRun(const std::string &name, std::size_t n_jobs)
      : dir(fs::temp_directory_path() / (name + "_" + std::to_string(::getpid()))), run((fs::remove_all(dir), dir)) {
    options.quiet = true;
    batch.total = n_jobs;
    run.update_manifest([&](nlohmann::json &m) {
      m["cases"] = nlohmann::json::array();
      for (std::size_t i = 0; i < n_jobs; ++i) m["cases"].push_back({{"id", sm::RunDirectory::case_id(i)}});
    });
    for (std::size_t i = 0; i < n_jobs; ++i) {
      sm::CaseJob job;
      job.index = i;
      job.request.id = sm::RunDirectory::case_id(i);
      batch.jobs.push_back(job);
    }
  }
  ~PoolRun() { fs::remove_all(dir); }
  nlohmann::json record(std::size_t i) const { return run.manifest()["cases"][i]; }

  fs::path dir;
  sm::RunDirectory run;
  sm::Workflow wf;
  sm::Scene scene;
  sm::PluginRegistry registry{std::vector<fs::path>{}};
  sm::RunOptions options;
  sm::StageContext ctx{wf, scene, run, registry, options};
  sm::CaseBatch batch;
};

sm::CaseOutcome succeeded(const sm::CaseJob &job) {
  sm::CaseOutcome o;
  o.index = job.index;
  o.id = job.request.id;
  o.ok = true;
  o.result = {{"steps", 100.0}, {"particle_steps_per_second", 1e6}, {"removed", 0.0}};
  o.start = o.end = sm::RunDirectory::now_iso();
  o.wall_seconds = 0.01;
  o.host = "here";
  return o;
}

sm::CaseOutcome failed(const sm::CaseJob &job, int exit_code, const std::string &error) {
  sm::CaseOutcome o = succeeded(job);
  o.ok = false;
  o.result = nullptr;
  o.exit_code = exit_code;
  o.error = error;
  return o;
}

// Waits (at most 20 s, so that a broken executor fails the test instead of hanging it) until `ready`.
template <class Ready> bool wait_for(std::mutex &m, std::condition_variable &cv, Ready ready) {
  std::unique_lock<std::mutex> lock(m);
  return cv.wait_for(lock, std::chrono::seconds(20), ready);
}

// Sets `seen` once a log line containing `text` is written.
class WatchSink : public spdlog::sinks::base_sink<std::mutex> {
 public:
  explicit WatchSink(std::string text) : text_(std::move(text)) {}
  std::atomic<bool> seen{false};

 protected:
  void sink_it_(const spdlog::details::log_msg &msg) override {
    if (std::string(msg.payload.data(), msg.payload.size()).find(text_) != std::string::npos) seen = true;
  }
  void flush_() override {}

 private:
  std::string text_;
};

}  // namespace

TEST(LocalExecutor, EveryJobRunsExactlyOnceOnAPoolOfJobsThreads) {
  constexpr int n = 20, pool = 3;
  PoolRun r("spreadmap_pool", n);
  std::vector<std::atomic<int>> runs(n);
  std::vector<int> threads(n, -1);
  std::mutex m;
  std::condition_variable cv;
  int running = 0, most = 0;
  sm::LocalExecutor executor(pool, 0, [&](const sm::CaseJob &job, sm::PluginRegistry &) {
    ++runs[job.index];
    {
      std::lock_guard<std::mutex> g(m);
      threads[job.index] = job.request.threads;
      most = std::max(most, ++running);
    }
    cv.notify_all();
    // the first jobs wait until the pool is full: with fewer threads they would wait in vain
    if (job.index < pool) wait_for(m, cv, [&] { return most >= pool; });
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
    {
      std::lock_guard<std::mutex> g(m);
      --running;
    }
    return succeeded(job);
  });
  executor.run_cases(r.batch, r.ctx);
  EXPECT_EQ(most, pool) << "cases running at once";
  const int share = std::max(1, int(std::thread::hardware_concurrency()) / pool);
  for (int i = 0; i < n; ++i) {
    EXPECT_EQ(runs[i].load(), 1) << i;
    EXPECT_EQ(threads[i], share) << "each case gets its share of the cores";
    EXPECT_EQ(r.record(i).value("status", ""), "done") << r.record(i).dump();
    EXPECT_EQ(r.record(i).value("host", ""), "here") << r.record(i).dump();
  }
}

TEST(LocalExecutor, ThreadsPerCaseComeFromTheOptionThenTheSceneThenTheCoresShare) {
  sm::Scene five, all;
  five.threads = 5;
  EXPECT_EQ(sm::LocalExecutor(4, 7).threads_for(five, 4), 7);
  EXPECT_EQ(sm::LocalExecutor(4).threads_for(five, 4), 5);
  const int cores = int(std::thread::hardware_concurrency());
  EXPECT_EQ(sm::LocalExecutor(4).threads_for(all, 2), std::max(1, cores / 2));
  EXPECT_EQ(sm::LocalExecutor(4).threads_for(all, 4 * cores), 1);
}

TEST(LocalExecutor, WithoutJobsOneCaseRunsOnTheCpuAndOnePerCoreOnTheGpu) {
  using sm::cuda::Backend;
  EXPECT_EQ(sm::LocalExecutor::cases_at_once(0, Backend::cpu, 45, 16), 1) << "a CPU case takes every core";
  EXPECT_EQ(sm::LocalExecutor::cases_at_once(0, Backend::cuda, 45, 16), 16) << "a host thread a case";
  EXPECT_EQ(sm::LocalExecutor::cases_at_once(0, Backend::cuda, 8, 16), 8) << "never more than the cases";
  EXPECT_EQ(sm::LocalExecutor::cases_at_once(0, Backend::cuda, 3, 0), 1) << "an unknown core count is one";
  EXPECT_EQ(sm::LocalExecutor::cases_at_once(3, Backend::cpu, 45, 16), 3) << "--jobs decides when given";
  EXPECT_EQ(sm::LocalExecutor::cases_at_once(3, Backend::cuda, 2, 16), 2);
  EXPECT_EQ(sm::LocalExecutor::cases_at_once(0, Backend::cuda, 0, 16), 1);
}

TEST(LocalExecutor, AFailureIsThrownOnceTheRunningCaseFinishedAndWasRecorded) {
  constexpr int n = 8;
  PoolRun r("spreadmap_pool_failure", n);
  // c001 fails while c000 runs; c000 goes on until the failure has come to the executor (it logs
  // a failure that other cases outlive), then finishes
  auto watch = std::make_shared<WatchSink>("c001: the stand-in became unstable");
  spdlog::default_logger()->sinks().push_back(watch);
  std::vector<std::atomic<int>> runs(n);
  std::atomic<bool> c000_finished{false};
  sm::LocalExecutor executor(2, 0, [&](const sm::CaseJob &job, sm::PluginRegistry &) {
    ++runs[job.index];
    if (job.index == 1) return failed(job, sm::exit_failure, "the stand-in became unstable");
    if (job.index == 0) {
      const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
      while (!watch->seen && std::chrono::steady_clock::now() < deadline)
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
      c000_finished = true;
    }
    return succeeded(job);
  });
  try {
    executor.run_cases(r.batch, r.ctx);
    ADD_FAILURE() << "the failure was not thrown";
  } catch (const sm::RunFailure &e) {
    EXPECT_EQ(std::string(e.what()), "the stand-in became unstable");
    EXPECT_TRUE(c000_finished) << "thrown while c000 was running";
    EXPECT_EQ(r.record(0).value("status", ""), "done") << r.record(0).dump();
  }
  spdlog::default_logger()->sinks().pop_back();
  EXPECT_TRUE(watch->seen);
  EXPECT_EQ(runs[0].load(), 1);
  EXPECT_EQ(runs[1].load(), 1);
  for (int i = 2; i < n; ++i) EXPECT_EQ(runs[i].load(), 0) << "c00" << i << " started after the failure";
  EXPECT_FALSE(r.record(1).contains("status")) << r.record(1).dump();
}

// Last in this file: a stop request cannot be taken back in a process (CTest runs each test in its own).
TEST(LocalExecutor, AStopRequestLeavesTheUnstartedJobsUnrun) {
  constexpr int n = 6;
  PoolRun r("spreadmap_pool_stop", n);
  std::vector<std::atomic<int>> runs(n);
  std::mutex m;
  std::condition_variable cv;
  int started = 0;
  sm::LocalExecutor executor(2, 0, [&](const sm::CaseJob &job, sm::PluginRegistry &) {
    ++runs[job.index];
    {
      std::lock_guard<std::mutex> g(m);
      ++started;
    }
    cv.notify_all();
    wait_for(m, cv, [&] { return started >= 2; });  // both cases are running
    if (job.index == 0) {
      sm::request_stop();  // as SIGINT does; c000 was about to finish
      return succeeded(job);
    }
    // c001 sees the request at its next step, as a case does, and keeps a checkpoint
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
    while (!sm::stop_requested() && std::chrono::steady_clock::now() < deadline)
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    return failed(job, sm::exit_interrupted,
                  "interrupted: c001 saved its checkpoint; run the same command again to resume");
  });
  try {
    executor.run_cases(r.batch, r.ctx);
    ADD_FAILURE() << "the stop was not reported";
  } catch (const sm::Interrupted &e) {
    EXPECT_EQ(e.exit_code, 130);
    EXPECT_NE(std::string(e.what()).find("c001 saved its checkpoint"), std::string::npos) << e.what();
  }
  EXPECT_EQ(runs[0].load(), 1);
  EXPECT_EQ(runs[1].load(), 1);
  for (int i = 2; i < n; ++i) EXPECT_EQ(runs[i].load(), 0) << "c00" << i << " started after the stop request";
  EXPECT_EQ(r.record(0).value("status", ""), "done") << "a case finished before the stop is kept";
  EXPECT_FALSE(r.record(1).contains("status")) << r.record(1).dump();
}
