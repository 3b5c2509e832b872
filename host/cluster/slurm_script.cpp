#include "cluster/slurm_script.hpp"

#include <fmt/format.h>
#include <sys/stat.h>

#include <algorithm>
#include <nlohmann/json.hpp>

#include "core/files.hpp"
#include "core/suggest.hpp"

namespace spreadmap::cluster {
namespace {

// A path in an #SBATCH line: sbatch reads these itself (no shell), and takes double quotes.
std::string directive_path(const fs::path &p) {
  const std::string s = p.string();
  return s.find_first_of(" \t") == std::string::npos ? s : "\"" + s + "\"";
}

std::string header(const SlurmPlan &plan, const std::string &what) {
  return fmt::format(
      "#!/bin/bash\n"
      "# spreadmap, workflow '{}': {}.\n"
      "# Written by `spreadmap run --executor slurm` (and rewritten by its next call); submit.sh beside\n"
      "# it submits every job in order. Partition, account and time limit: sbatch's own options, or its\n"
      "# variables SBATCH_PARTITION, SBATCH_ACCOUNT and SBATCH_TIMELIMIT.\n",
      plan.name, what);
}

std::string run_command(const SlurmPlan &plan) {
  return shell_quote(plan.binary.string()) + " run " + shell_quote(plan.workflow.string()) + " --out " +
         shell_quote(plan.out.string());
}

}  // namespace

std::string array_spec(std::vector<std::size_t> cases) {
  std::sort(cases.begin(), cases.end());
  cases.erase(std::unique(cases.begin(), cases.end()), cases.end());
  std::string out;
  for (std::size_t i = 0; i < cases.size();) {
    std::size_t j = i;
    while (j + 1 < cases.size() && cases[j + 1] == cases[j] + 1) ++j;
    if (!out.empty()) out += ",";
    out += std::to_string(cases[i]);
    if (j > i) out += "-" + std::to_string(cases[j]);
    i = j + 1;
  }
  return out;
}

std::string shell_quote(const std::string &word) {
  std::string out = "'";
  for (const char c : word) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

std::string case_array_script(const SlurmPlan &plan, const std::vector<std::size_t> &cases, const std::string &role) {
  std::string s = header(plan, "cases " + array_spec(cases) + " of the simulate stage as a job array (" + role + ")");
  s += "# Array task k runs case k of the design (case 7 is cases/c007) and nothing else: it leaves\n"
       "# the other cases and manifest.json alone, so the tasks may run at once on any nodes that share\n"
       "# the run folder. A task run again resumes its case from its checkpoint, or finds it finished.\n";
  s += fmt::format("#SBATCH --job-name=spreadmap-{}-cases\n", plan.name);
  s += "#SBATCH --array=" + array_spec(cases) + "\n";
  s += "#SBATCH --ntasks=1\n";
  s += fmt::format("#SBATCH --cpus-per-task={}\n", plan.threads);
  s += "#SBATCH --output=" + directive_path(plan.out / "slurm" / "logs" / "case-%a.log") + "\n";
  s += "set -euo pipefail\n";
  s += ": \"${SLURM_ARRAY_TASK_ID:?is not set: submit this script with sbatch, or set it to a case number}\"\n";
  s += fmt::format("threads=\"${{SLURM_CPUS_PER_TASK:-{}}}\"\n", plan.threads);
  s += "export OMP_NUM_THREADS=\"$threads\"\n";
  s += "exec " + run_command(plan) + " --case \"$SLURM_ARRAY_TASK_ID\" --threads-per-rank \"$threads\"" +
       (plan.force ? " --force" : "") + "\n";
  return s;
}

std::string stages_script(const SlurmPlan &plan) {
  const std::string stages = plan.stages.empty() ? "every stage" : join(plan.stages);
  std::string s = header(plan, "the stages after the cases (" + stages + "), once every case is done");
  s += "# It runs once every case has finished: the simulate stage then finds them all done and records\n"
       "# them in manifest.json, and the later stages run as they would on one machine.\n";
  s += fmt::format("#SBATCH --job-name=spreadmap-{}-stages\n", plan.name);
  s += "#SBATCH --ntasks=1\n";
  s += fmt::format("#SBATCH --cpus-per-task={}\n", plan.threads);
  s += "#SBATCH --output=" + directive_path(plan.out / "slurm" / "logs" / "stages.log") + "\n";
  s += "set -euo pipefail\n";
  s += fmt::format("export OMP_NUM_THREADS=\"${{SLURM_CPUS_PER_TASK:-{}}}\"\n", plan.threads);
  s += "exec " + run_command(plan) + (plan.stages.empty() ? "" : " --only " + join(plan.stages, ",")) +
       (plan.stages_force ? " --force" : "") + "\n";
  return s;
}

SlurmFiles slurm_files(const SlurmPlan &plan) {
  SlurmFiles f;
  f.dir = plan.out / "slurm";
  if (!plan.heap_cases.empty()) f.heap_cases = f.dir / "heap_cases.sbatch";
  if (!plan.other_cases.empty()) f.other_cases = f.dir / "cases.sbatch";
  f.stages = f.dir / "stages.sbatch";
  f.submit = f.dir / "submit.sh";
  return f;
}

std::string submit_script(const SlurmPlan &plan, const SlurmFiles &files) {
  std::string s = header(plan, "submits the jobs of the run");
  s += "# Run it with bash; it prints one line per job: its id and what it runs.\n";
  s += "# A job sbatch refuses stops it there (set -e); sbatch --parsable prints \"id\" or \"id;cluster\".\n";
  s += "set -euo pipefail\n";
  std::vector<std::string> before;  // the jobs the next one waits for
  auto after = [&] {
    if (before.empty()) return std::string();
    std::string deps = "--dependency=afterok";
    for (const auto &b : before) deps += ":$" + b;
    return deps + " --kill-on-invalid-dep=yes ";
  };
  auto waits = [&] {
    if (before.empty()) return std::string();
    std::string w = before.size() == 1 ? ", after job" : ", after jobs";
    for (const auto &b : before) w += " $" + b;
    return w;
  };
  std::vector<std::string> cases_jobs;
  if (!files.heap_cases.empty()) {
    s += "heap_job=$(sbatch --parsable " + shell_quote(files.heap_cases.string()) + ")\n";
    s += "heap_job=${heap_job%%;*}\n";
    s += "echo \"submitted job $heap_job: cases " + array_spec(plan.heap_cases) +
         " (array), each settling the powder heap the other cases reuse\"\n";
    cases_jobs.push_back("heap_job");
  }
  if (!files.other_cases.empty()) {
    before = cases_jobs;
    s += "cases_job=$(sbatch --parsable " + after() + shell_quote(files.other_cases.string()) + ")\n";
    s += "cases_job=${cases_job%%;*}\n";
    s += "echo \"submitted job $cases_job: cases " + array_spec(plan.other_cases) + " (array)" + waits() + "\"\n";
    cases_jobs.push_back("cases_job");
  }
  before = cases_jobs;
  s += "stages_job=$(sbatch --parsable " + after() + shell_quote(files.stages.string()) + ")\n";
  s += "stages_job=${stages_job%%;*}\n";
  s += "echo \"submitted job $stages_job: " + (plan.stages.empty() ? std::string("every stage") : join(plan.stages)) +
       waits() + "\"\n";
  return s;
}

SlurmFiles write_slurm_files(const SlurmPlan &plan) {
  const SlurmFiles f = slurm_files(plan);
  fs::create_directories(f.dir / "logs");
  auto write = [](const fs::path &p, const std::string &text) {
    write_atomic(p, text);
    fs::permissions(p, fs::perms::owner_exec | fs::perms::group_exec | fs::perms::others_exec, fs::perm_options::add);
  };
  // stale scripts of an earlier call would be submitted by hand by mistake
  for (const char *name : {"heap_cases.sbatch", "cases.sbatch"}) fs::remove(f.dir / name);
  if (!f.heap_cases.empty())
    write(f.heap_cases,
          case_array_script(plan, plan.heap_cases, "each settles a powder heap that the other cases reuse"));
  if (!f.other_cases.empty())
    write(f.other_cases, case_array_script(plan, plan.other_cases,
                                           plan.heap_cases.empty() ? "their powder heaps are settled already"
                                                                   : "they start once heap_cases.sbatch is done"));
  write(f.stages, stages_script(plan));
  write(f.submit, submit_script(plan, f));
  return f;
}

}  // namespace spreadmap::cluster
