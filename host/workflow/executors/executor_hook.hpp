// Where the simulate stage's cases run: here in --jobs threads (local_executor.hpp, the default), on
// MPI ranks or as a Slurm job array (host/cluster/). The stage decides which cases are unfinished; an
// executor only decides where each of them runs, and every executor records, logs and reports a
// case's outcome with the functions below, so that resume and failures read the same on all of them.
// A case travels between processes as JSON (a CaseJob), and comes back as a CaseOutcome; both are
// plain data so that any rank can rebuild them.
#pragma once
#include <cstddef>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/registry.hpp"
#include "workflow/cases/case_runner.hpp"

namespace spreadmap {

class RunDirectory;
struct StageContext;

// One unfinished case of the design.
struct CaseJob {
  std::size_t index = 0;  // position in the design: c000 is 0
  CaseRequest request;    // `progress` is never sent; `threads` is set where the case runs
  bool render = false;    // draw cases/cNNN/snapshot.png after the run
};

// What became of one case, wherever it ran.
struct CaseOutcome {
  std::size_t index = 0;
  std::string id;
  bool ok = false;
  int exit_code = 0;      // of the error, when !ok (130: interrupted, resumable)
  std::string error;      // the message, when !ok
  nlohmann::json result;  // case.json, when ok
  std::string start, end;
  double wall_seconds = 0;
  int rank = 0;  // MPI rank (0 when not under MPI)
  std::string host;
};

// The simulate stage's unfinished cases, in design order.
struct CaseBatch {
  std::vector<CaseJob> jobs;
  std::size_t total = 0;           // cases in the design, finished ones included
  std::string label = "simulate";  // of the progress line
};

class CaseExecutor {
 public:
  virtual ~CaseExecutor() = default;
  // Runs (or hands out, or submits) every job; throws the first failure once nothing is running.
  virtual void run_cases(CaseBatch &batch, StageContext &ctx) = 0;
  // False when the cases were only submitted (Slurm): the later stages then wait for them in a
  // dependent job, and this process stops after simulate.
  virtual bool runs_later_stages() const { return true; }
  // Called before any stage other than simulate: from here on this process works alone (an MPI
  // rank 0 lets its workers exit). Called more than once; only the first call does anything.
  virtual void release() {}
};

nlohmann::json job_to_json(const CaseJob &job);
CaseJob job_from_json(const nlohmann::json &j);
nlohmann::json outcome_to_json(const CaseOutcome &o);
CaseOutcome outcome_from_json(const nlohmann::json &j);

// Runs one case in this process (and draws its snapshot when asked). Never throws for a failed
// case: the failure is in the outcome, so that a worker can report it and go on.
CaseOutcome run_case_job(const CaseJob &job, PluginRegistry &registry);
// A finished case whose snapshot.png is missing or torn (a kill or a full disk between case.json and
// the figure) gets it drawn again from its state and record.
void redraw_missing_snapshot(const CaseRequest &req);

// Marks the outcome failed by `e`, with its exit code (an Error's, else exit_failure).
void set_failure(CaseOutcome &outcome, const std::exception &e);

// "c001 done[ on rank 2 (node7)]: steps, wall time, speed, removed", as the local path says it.
void log_done(const CaseOutcome &outcome, const std::string &where = "");

// A failed case, logged when it comes unless it is thrown at once (the first failure, with no other
// case running; main prints that one): as an error, or as a note when the case was interrupted.
void log_failure(const CaseOutcome &outcome, const std::string &where);

// The case's entry in manifest.json, as the local path writes it (start, end, wall_seconds,
// status), plus the rank and host it ran on.
void record_outcome(RunDirectory &run, const CaseOutcome &outcome);

// The exception a failed outcome stands for, with the same exit code; `where` (" on rank 2 (node7)")
// is put before the message.
[[noreturn]] void throw_outcome(const CaseOutcome &outcome, const std::string &where);

}  // namespace spreadmap
