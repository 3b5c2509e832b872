// The Slurm scripts of `spreadmap run WORKFLOW --executor slurm`, as text: job arrays of the
// simulate stage's cases (array task k runs case k of the design, `spreadmap run ... --case k`),
// a job for the later stages that waits for them, and submit.sh, which submits all of them in
// order with sbatch and prints the job ids. Plain functions of a plan, so tests can read them.
#pragma once
#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

namespace spreadmap::cluster {

namespace fs = std::filesystem;

struct SlurmPlan {
  std::string name;                      // the workflow's: job names are spreadmap-<name>-...
  fs::path binary, workflow, out;        // absolute: the jobs may start in another folder
  int threads = 1;                       // --cpus-per-task of each case (and of the stages job)
  bool force = false;                    // recompute the cases (the array tasks get --force)
  std::vector<std::size_t> heap_cases;   // first array: each settles a heap the others reuse
  std::vector<std::size_t> other_cases;  // second array, after the first
  std::vector<std::string> stages;       // --only of the stages job; empty: every stage
  bool stages_force = false;
};

// Slurm's --array syntax for case numbers: {0,1,2,3,5,7,8} -> "0-3,5,7-8".
std::string array_spec(std::vector<std::size_t> cases);
// One word for bash, whatever it holds.
std::string shell_quote(const std::string &word);

std::string case_array_script(const SlurmPlan &plan, const std::vector<std::size_t> &cases, const std::string &role);
std::string stages_script(const SlurmPlan &plan);

// The files under <out>/slurm/, written by write_slurm_files.
struct SlurmFiles {
  fs::path dir, heap_cases, other_cases, stages, submit;  // an empty path: no such job (no case of that kind)
};
SlurmFiles slurm_files(const SlurmPlan &plan);
std::string submit_script(const SlurmPlan &plan, const SlurmFiles &files);
// Writes every script (atomically, executable) and makes the log folder; returns their paths.
SlurmFiles write_slurm_files(const SlurmPlan &plan);

}  // namespace spreadmap::cluster
