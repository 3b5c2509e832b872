// --executor slurm without a Slurm: the scripts it writes are checked as text and by bash, then run
// the way Slurm would run them (bash, with SLURM_ARRAY_TASK_ID set), and their results compared with
// a serial run's. sbatch itself is a stand-in that records its arguments and answers like the real
// one. The one-node Slurm on localhost is slurm_localhost.sh.
#include <gtest/gtest.h>

#include <memory>

#include "cluster/cluster_support.hpp"
#include "cluster/slurm_script.hpp"

namespace fs = std::filesystem;
namespace t = spreadmap::test;
namespace cl = spreadmap::cluster;

namespace {

t::Command spreadmap_command(std::vector<std::string> args, std::map<std::string, std::string> env = {}) {
  return {std::move(args), {}, std::move(env), {}};
}

t::Outcome dry_run(const fs::path &run) {
  return t::run(spreadmap_command(
      {"run", t::mini_quickstart().string(), "--out", run.string(), "--executor", "slurm", "--dry-run"}));
}

// An array script run as Slurm runs one of its tasks.
t::Command array_task(const fs::path &script, int task) {
  return {{script.string()}, "/bin/bash", {{"SLURM_ARRAY_TASK_ID", std::to_string(task)}}, {}};
}

std::string sbatch_line(const std::string &script, const std::string &name) {
  for (std::size_t at = 0, end; (end = script.find('\n', at)) != std::string::npos; at = end + 1)
    if (script.compare(at, 8 + name.size() + 1, "#SBATCH " + name + "=") == 0) return script.substr(at, end - at);
  return "";
}

void expect_valid_bash(const fs::path &script) {
  const t::Outcome check = t::run({{"-n", script.string()}, "/bin/bash", {}, {}});
  EXPECT_EQ(check.exit_code, 0) << script << ":\n" << check.describe();
}

}  // namespace

TEST(SlurmScript, ArraySpecListsCaseNumbersAsRanges) {
  EXPECT_EQ(cl::array_spec({0, 1, 2, 3}), "0-3");
  EXPECT_EQ(cl::array_spec({8, 0, 1, 2, 3, 5, 7}), "0-3,5,7-8");
  EXPECT_EQ(cl::array_spec({4}), "4");
  EXPECT_EQ(cl::array_spec({1, 1, 2}), "1-2");
  EXPECT_EQ(cl::array_spec({}), "");
}

TEST(SlurmScript, ShellQuoteKeepsAnyPathOneWord) {
  EXPECT_EQ(cl::shell_quote("/runs/a b"), "'/runs/a b'");
  EXPECT_EQ(cl::shell_quote("it's"), "'it'\\''s'");
  EXPECT_EQ(cl::shell_quote("$HOME"), "'$HOME'");
}

// The first case settles the powder heap that the three others reuse: it is an array of its own,
// and the others wait for it (afterok), as does the job of the later stages for all of them.
TEST(SlurmExecutor, DryRunWritesBashScriptsWithTheRightArrays) {
  t::Scratch scratch("slurm_dry");
  const fs::path run = scratch.dir / "run", dir = run / "slurm";
  const t::Outcome out = dry_run(run);
  ASSERT_EQ(out.exit_code, 0) << out.describe();
  EXPECT_EQ(out.out, (dir / "submit.sh").string() + "\n") << "the path of the script, alone on stdout";
  for (const char *f : {"heap_cases.sbatch", "cases.sbatch", "stages.sbatch", "submit.sh"}) {
    ASSERT_TRUE(fs::exists(dir / f)) << f;
    expect_valid_bash(dir / f);
  }
  const std::string heap = t::slurp(dir / "heap_cases.sbatch"), cases = t::slurp(dir / "cases.sbatch"),
                    stages = t::slurp(dir / "stages.sbatch"), submit = t::slurp(dir / "submit.sh");
  EXPECT_EQ(sbatch_line(heap, "--array"), "#SBATCH --array=0");
  EXPECT_EQ(sbatch_line(cases, "--array"), "#SBATCH --array=1-3");
  EXPECT_EQ(sbatch_line(stages, "--array"), "");
  for (const auto *s : {&heap, &cases}) {
    EXPECT_TRUE(t::contains(*s, " --out '" + run.string() + "' --case \"$SLURM_ARRAY_TASK_ID\"")) << *s;
    EXPECT_EQ(sbatch_line(*s, "--cpus-per-task"), "#SBATCH --cpus-per-task=1") << "scene.threads of the workflow";
  }
  EXPECT_FALSE(t::contains(stages, "--case")) << stages;
  EXPECT_TRUE(t::contains(
      submit, "--dependency=afterok:$heap_job --kill-on-invalid-dep=yes '" + (dir / "cases.sbatch").string()))
      << submit;
  EXPECT_TRUE(t::contains(submit, "--dependency=afterok:$heap_job:$cases_job --kill-on-invalid-dep=yes '" +
                                      (dir / "stages.sbatch").string()))
      << submit;
  // nothing was computed; the cases are recorded for the stages job
  for (int i = 0; i < t::mini_cases; ++i) EXPECT_FALSE(fs::exists(run / "cases" / t::case_id(i) / "state.vtp")) << i;
  EXPECT_EQ(t::manifest(run).at("cases").size(), std::size_t(t::mini_cases));
}

// Run as Slurm would: the first array, then the other array's tasks all at once, then the stages
// job. The array tasks leave manifest.json alone; the result is the serial run's, byte for byte.
TEST(SlurmExecutor, ScriptsRunAsSlurmWouldGiveTheSerialRunsMetrics) {
  t::Scratch scratch("slurm_by_hand");
  const t::Outcome serial = t::serial_run(scratch.dir / "serial");
  ASSERT_EQ(serial.exit_code, 0) << serial.describe();
  const fs::path run = scratch.dir / "run", dir = run / "slurm";
  ASSERT_EQ(dry_run(run).exit_code, 0);
  const t::FileId manifest = t::identify(run / "manifest.json");

  const t::Outcome heap = t::run(array_task(dir / "heap_cases.sbatch", 0));
  ASSERT_EQ(heap.exit_code, 0) << heap.describe();
  EXPECT_TRUE(t::contains(heap.err, "simulate: case c000 of 4: to run")) << heap.err;
  {
    std::vector<std::unique_ptr<t::Child>> tasks;
    for (int k = 1; k < t::mini_cases; ++k)
      tasks.push_back(std::make_unique<t::Child>(array_task(dir / "cases.sbatch", k)));
    for (auto &task : tasks) {
      const t::Outcome o = task->wait();
      EXPECT_EQ(o.exit_code, 0) << o.describe();
      EXPECT_FALSE(t::contains(o.err, "inserted")) << "a task settled the heap again:\n" << o.err;
    }
  }
  EXPECT_EQ(t::identify(run / "manifest.json"), manifest) << "an array task wrote manifest.json";
  // a task run twice (a requeued one) finds its case finished
  const t::Outcome again = t::run(array_task(dir / "cases.sbatch", 2));
  EXPECT_TRUE(t::contains(again.err, "simulate: case c002 of 4: finished already")) << again.describe();

  const t::Outcome stages = t::run({{(dir / "stages.sbatch").string()}, "/bin/bash", {}, {}});
  ASSERT_EQ(stages.exit_code, 0) << stages.describe();
  EXPECT_TRUE(t::contains(stages.err, "4 cases, 0 to run, 4 finished already")) << stages.err;
  EXPECT_EQ(t::slurp(run / "metrics.csv"), t::slurp(scratch.dir / "serial/metrics.csv"));
  for (const auto &c : t::manifest(run).at("cases")) EXPECT_EQ(c.value("status", ""), "done") << c.dump();

  // once the heap is on disk, a new dry run has no heap array: every unfinished case at once
  fs::remove_all(run / "cases/c001");
  fs::remove_all(run / "cases/c003");
  ASSERT_EQ(dry_run(run).exit_code, 0);
  EXPECT_FALSE(fs::exists(dir / "heap_cases.sbatch"));
  EXPECT_EQ(sbatch_line(t::slurp(dir / "cases.sbatch"), "--array"), "#SBATCH --array=1,3");
}

// Without --dry-run, submit.sh runs sbatch (here a stand-in on PATH) and the job ids come out.
TEST(SlurmExecutor, SubmitsInOrderAndPrintsTheJobIds) {
  t::Scratch scratch("slurm_submit");
  const fs::path bin = scratch.dir / "bin", log = scratch.dir / "sbatch.log", run = scratch.dir / "run";
  fs::create_directories(bin);
  std::ofstream(bin / "sbatch") << "#!/bin/bash\n"
                                   "# stands in for Slurm's sbatch: records its arguments, answers as --parsable does\n"
                                   "n=$(( $(cat \"$SBATCH_LOG\" 2>/dev/null | wc -l) + 101 ))\n"
                                   "echo \"$*\" >> \"$SBATCH_LOG\"\n"
                                   "echo \"$n;cluster\"\n";
  fs::permissions(bin / "sbatch", fs::perms::owner_all);
  const std::string path = bin.string() + ":/usr/bin:/bin";
  const t::Outcome out =
      t::run(spreadmap_command({"run", t::mini_quickstart().string(), "--out", run.string(), "--executor", "slurm"},
                               {{"PATH", path}, {"SBATCH_LOG", log.string()}}));
  ASSERT_EQ(out.exit_code, 0) << out.describe();
  const fs::path dir = run / "slurm";
  EXPECT_EQ(out.out,
            "submitted job 101: cases 0 (array), each settling the powder heap the other cases reuse\n"
            "submitted job 102: cases 1-3 (array), after job 101\n"
            "submitted job 103: every stage, after jobs 101 102\n");
  EXPECT_EQ(t::slurp(log), "--parsable " + (dir / "heap_cases.sbatch").string() + "\n" +
                               "--parsable --dependency=afterok:101 --kill-on-invalid-dep=yes " +
                               (dir / "cases.sbatch").string() + "\n" +
                               "--parsable --dependency=afterok:101:102 --kill-on-invalid-dep=yes " +
                               (dir / "stages.sbatch").string() + "\n");
}

TEST(SlurmExecutor, WithoutSbatchTheErrorSaysWhereTheScriptsAre) {
  t::Scratch scratch("slurm_missing");
  const fs::path empty = scratch.dir / "empty", run = scratch.dir / "run";
  fs::create_directories(empty);
  const t::Outcome out =
      t::run(spreadmap_command({"run", t::mini_quickstart().string(), "--out", run.string(), "--executor", "slurm"},
                               {{"PATH", empty.string()}}));
  EXPECT_EQ(out.exit_code, 2) << out.describe();
  EXPECT_TRUE(t::contains(out.err, "sbatch was not found on PATH")) << out.err;
  EXPECT_TRUE(t::contains(out.err, "bash " + (run / "slurm/submit.sh").string())) << out.err;
  EXPECT_TRUE(fs::exists(run / "slurm/submit.sh"));
  EXPECT_EQ(t::crash_marker(out.err), "") << out.err;
}

// sbatch refusing a job (a wrong partition, say) stops the submission with its message.
TEST(SlurmExecutor, ARefusedJobIsAnError) {
  t::Scratch scratch("slurm_refused");
  const fs::path bin = scratch.dir / "bin", run = scratch.dir / "run";
  fs::create_directories(bin);
  std::ofstream(bin / "sbatch") << "#!/bin/bash\necho 'sbatch: error: invalid partition specified: nope' >&2\nexit 1\n";
  fs::permissions(bin / "sbatch", fs::perms::owner_all);
  const t::Outcome out =
      t::run(spreadmap_command({"run", t::mini_quickstart().string(), "--out", run.string(), "--executor", "slurm"},
                               {{"PATH", bin.string() + ":/usr/bin:/bin"}}));
  EXPECT_EQ(out.exit_code, 1) << out.describe();
  EXPECT_TRUE(t::contains(out.err, "invalid partition specified")) << out.err;
  EXPECT_TRUE(t::contains(out.err, "sbatch refused a job")) << out.err;
  EXPECT_EQ(out.out, "");
}
