// The command line of the executors: options that do not go together are refused before anything
// runs (exit 2, a message naming the option), and --case runs exactly one case.
#include <gtest/gtest.h>

#include "cluster/cluster_support.hpp"

namespace fs = std::filesystem;
namespace t = spreadmap::test;

namespace {

t::Outcome spreadmap_run(const fs::path &out, std::vector<std::string> extra) {
  std::vector<std::string> args = {"run", t::mini_quickstart().string(), "--out", out.string()};
  args.insert(args.end(), extra.begin(), extra.end());
  return t::run({args, {}, {}, {}});
}

}  // namespace

TEST(ExecutorOptions, MismatchedOptionsAreRefusedBeforeAnythingRuns) {
  t::Scratch scratch("options");
  const fs::path run = scratch.dir / "run";
  const std::vector<std::pair<std::vector<std::string>, std::string>> refused = {
      {{"--executor", "slrum"}, "did you mean 'slurm'?"},
      {{"--dry-run"}, "--dry-run writes the Slurm scripts"},
      {{"--executor", "mpi", "--jobs", "2"}, "--jobs is for the local executor"},
      {{"--threads-per-rank", "2"}, "--threads-per-rank is for --executor mpi or slurm"},
      {{"--executor", "slurm", "--threads-per-rank", "0"}, "--threads-per-rank must be at least 1"},
      {{"--case", "1", "--executor", "mpi"}, "--case runs one case here"},
      {{"--case", "1", "--only", "characterise"}, "--only characterise does not go with it"},
      {{"--case", "4"}, "--case 4: the design has 4 cases, numbered 0 to 3"},
      {{"--executor", "slurm", "--dry-run", "--only", "characterise"}, "no simulate stage selected"},
  };
  for (const auto &[args, message] : refused) {
    const t::Outcome o = spreadmap_run(run, args);
    std::string line;
    for (const auto &a : args) line += " " + a;
    EXPECT_EQ(o.exit_code, 2) << line << "\n" << o.describe();
    EXPECT_TRUE(t::contains(o.err, message)) << line << "\n" << o.err;
    EXPECT_EQ(t::crash_marker(o.err), "") << o.err;
    EXPECT_FALSE(fs::exists(run / "cases/c000/state.vtp")) << line;
  }
}

// `mpirun -n 2 spreadmap run WF` without --executor mpi would run every case twice into one folder.
TEST(ExecutorOptions, OneOfSeveralRanksWithoutTheMpiExecutorIsRefused) {
  t::Scratch scratch("ranks");
  const t::Outcome o = t::run({{"run", t::mini_quickstart().string(), "--out", (scratch.dir / "run").string()},
                               {},
                               {{"OMPI_COMM_WORLD_SIZE", "2"}},
                               {}});
  EXPECT_EQ(o.exit_code, 2) << o.describe();
  EXPECT_TRUE(t::contains(o.err, "every rank would run every case. Add --executor mpi")) << o.err;
  EXPECT_FALSE(fs::exists(scratch.dir / "run"));
}

TEST(ExecutorOptions, CaseRunsThatCaseOnlyAndLeavesTheManifestAlone) {
  t::Scratch scratch("one_case");
  const fs::path run = scratch.dir / "run";
  const t::Outcome o = spreadmap_run(run, {"--case", "2"});
  ASSERT_EQ(o.exit_code, 0) << o.describe();
  for (int i = 0; i < t::mini_cases; ++i)
    EXPECT_EQ(t::finished(run / "cases" / t::case_id(i)), i == 2) << t::case_id(i);
  EXPECT_FALSE(fs::exists(run / "manifest.json"));
  EXPECT_FALSE(fs::exists(run / "metrics.csv")) << "--case runs the simulate stage only";
}
