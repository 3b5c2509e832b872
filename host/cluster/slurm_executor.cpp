#include "cluster/slurm_executor.hpp"

#include <spdlog/spdlog.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <sstream>

#include "cluster/heap_order.hpp"
#include "workflow/run/run_dir.hpp"
#include "cluster/slurm_script.hpp"
#include "core/error.hpp"
#include "core/suggest.hpp"

namespace spreadmap::cluster {
namespace {

bool on_path(const std::string &program) {
  const char *path = std::getenv("PATH");
  std::stringstream dirs(path ? path : "");
  for (std::string dir; std::getline(dirs, dir, ':');) {
    std::error_code ec;
    const fs::path p = fs::path(dir.empty() ? "." : dir) / program;
    if (fs::is_regular_file(p, ec) && ::access(p.c_str(), X_OK) == 0) return true;
  }
  return false;
}

// The stages job: the selected stages as they are; under --force, only those after simulate (the
// array tasks recompute the cases themselves) and forced, so they follow the new cases.
void plan_stages(SlurmPlan &plan, const RunOptions &o, const Workflow &wf) {
  if (!o.force) {
    for (const auto &s : wf.stages)
      for (const auto &only : o.only)
        if (iequals(only, s.kind)) plan.stages.push_back(s.kind);
    return;
  }
  for (const auto &s : wf.stages) {
    bool selected = o.only.empty();
    for (const auto &only : o.only) selected |= iequals(only, s.kind);
    if (selected && s.kind != "simulate") plan.stages.push_back(s.kind);
  }
  plan.stages_force = !plan.stages.empty();
  if (plan.stages.empty()) plan.stages = {"simulate"};  // records the cases in manifest.json
}

// Runs submit.sh; its lines (one per job) are the answer.
std::string submit(const fs::path &script) {
  const std::string command = "bash " + shell_quote(script.string());
  std::FILE *pipe = ::popen(command.c_str(), "r");
  if (!pipe) throw RunFailure("--executor slurm: cannot start " + command);
  std::string out;
  char buf[512];
  while (std::fgets(buf, sizeof buf, pipe)) out += buf;
  const int status = ::pclose(pipe);
  if (status != 0)
    throw RunFailure("--executor slurm: sbatch refused a job (" + script.string() + " stopped" +
                     (out.empty() ? "" : " after:\n" + out) + "); its message is above. The scripts stay in " +
                     script.parent_path().string() + " to fix and submit by hand (bash " + script.string() + ")");
  return out;
}

}  // namespace

void SlurmExecutor::run_cases(CaseBatch &batch, StageContext &ctx) {
  SlurmPlan plan;
  plan.name = ctx.wf.name;
  plan.binary = fs::canonical("/proc/self/exe");
  plan.workflow = fs::absolute(ctx.wf.file);
  plan.out = fs::absolute(ctx.run.root());
  const int scene_threads = static_cast<int>(ctx.scene.threads);
  plan.threads = threads_ > 0 ? threads_ : scene_threads > 0 ? scene_threads : 1;
  plan.force = ctx.options.force;
  const HeapOrder order = order_by_heap(batch.jobs, ctx.registry);
  plan.heap_cases = order.first;
  plan.other_cases = order.rest;
  plan_stages(plan, ctx.options, ctx.wf);
  const SlurmFiles files = write_slurm_files(plan);
  spdlog::info("slurm: {} cases as array tasks ({} settling a heap first), then the stages job; scripts in {}",
               batch.jobs.size(), plan.heap_cases.size(), files.dir.string());
  if (dry_run_) {
    spdlog::info("slurm: --dry-run: nothing submitted; submit with: bash {}", files.submit.string());
    std::cout << files.submit.string() << std::endl;
    return;
  }
  if (!on_path("sbatch"))
    throw InputError(
        "--executor slurm: sbatch was not found on PATH, so nothing was submitted. Run this on a "
        "machine of the Slurm cluster (a login node), or submit the scripts written in " +
        files.dir.string() + " from one: bash " + files.submit.string());
  std::cout << submit(files.submit) << std::flush;
}

void SlurmExecutor::release() {
  throw InputError(
      "--executor slurm hands out the simulate stage's cases, and this run has none to hand out "
      "(no simulate stage selected); run the other stages without --executor");
}

}  // namespace spreadmap::cluster
