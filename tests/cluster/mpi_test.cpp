// --executor mpi against the serial run, on the reduced quickstart (tests/cluster/data/): the cases
// computed on other ranks give the same files byte for byte (deterministic mode: no thread or rank
// count enters the arithmetic), rank 0 alone keeps the manifest and runs characterise, and a rank-0
// error ends every rank instead of leaving workers waiting.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <set>

#include "cluster/cluster_support.hpp"

namespace fs = std::filesystem;
namespace t = spreadmap::test;

namespace {

// The distributed run's files against the serial run's: metrics.csv and every final state.
void expect_same_results(const fs::path &serial, const fs::path &mpi) {
  ASSERT_TRUE(fs::exists(mpi / "metrics.csv"));
  EXPECT_EQ(t::slurp(mpi / "metrics.csv"), t::slurp(serial / "metrics.csv")) << "metrics.csv differs";
  for (int i = 0; i < t::mini_cases; ++i) {
    const std::string id = t::case_id(i);
    EXPECT_EQ(t::slurp(mpi / "cases" / id / "state.vtp"), t::slurp(serial / "cases" / id / "state.vtp")) << id;
  }
}

}  // namespace

TEST(MpiExecutor, TwoRanksGiveTheSerialRunsMetricsByteForByte) {
  t::Scratch scratch("mpi2");
  const t::Outcome serial = t::serial_run(scratch.dir / "serial");
  ASSERT_EQ(serial.exit_code, 0) << serial.describe();
  const fs::path run = scratch.dir / "mpi";
  const t::Outcome mpi =
      t::run(t::under_mpirun(2, {"run", t::mini_quickstart().string(), "--out", run.string(), "--executor", "mpi"}));
  ASSERT_TRUE(mpi.exited) << mpi.describe();
  ASSERT_EQ(mpi.exit_code, 0) << mpi.describe();
  expect_same_results(scratch.dir / "serial", run);

  // rank 1 computed every case (rank 0 only hands them out), rank 0 recorded each once
  const auto m = t::manifest(run);
  ASSERT_EQ(m.at("cases").size(), std::size_t(t::mini_cases));
  for (const auto &c : m.at("cases")) {
    EXPECT_EQ(c.value("status", ""), "done") << c.dump();
    EXPECT_EQ(c.value("rank", -1), 1) << c.dump();
  }
  // characterise ran once, on rank 0, after the last case
  EXPECT_EQ(t::count(mpi.err, "characterise: 4 cases in metrics.csv"), 1u) << mpi.err;
  EXPECT_EQ(t::count(mpi.err, "[rank 1] c000: heap of 300 spheres inserted"), 1u) << mpi.err;
}

TEST(MpiExecutor, OneRankRunsTheCasesItself) {
  t::Scratch scratch("mpi1");
  const t::Outcome serial = t::serial_run(scratch.dir / "serial");
  ASSERT_EQ(serial.exit_code, 0) << serial.describe();
  const fs::path run = scratch.dir / "mpi";
  const t::Outcome mpi =
      t::run(t::under_mpirun(1, {"run", t::mini_quickstart().string(), "--out", run.string(), "--executor", "mpi"}));
  ASSERT_EQ(mpi.exit_code, 0) << mpi.describe();
  expect_same_results(scratch.dir / "serial", run);
  for (const auto &c : t::manifest(run).at("cases")) EXPECT_EQ(c.value("rank", -1), 0) << c.dump();
}

// Three ranks: two workers share the cases as they free up. The three cases after the first wait
// for its settled heap instead of settling it again, so exactly one heap is settled.
TEST(MpiExecutor, TwoWorkersShareTheCasesAndSettleTheHeapOnce) {
  t::Scratch scratch("mpi3");
  const fs::path run = scratch.dir / "mpi";
  const t::Outcome mpi =
      t::run(t::under_mpirun(3, {"run", t::mini_quickstart().string(), "--out", run.string(), "--executor", "mpi"}));
  ASSERT_EQ(mpi.exit_code, 0) << mpi.describe();
  EXPECT_EQ(t::count(mpi.err, "spheres inserted"), 1u) << mpi.err;
  EXPECT_EQ(t::count(mpi.err, "heap settled after"), 1u) << mpi.err;
  std::set<int> ranks;
  for (const auto &c : t::manifest(run).at("cases")) {
    EXPECT_EQ(c.value("status", ""), "done") << c.dump();
    ranks.insert(c.value("rank", -1));
  }
  for (const int r : ranks) EXPECT_TRUE(r == 1 || r == 2) << r;
  for (int i = 0; i < t::mini_cases; ++i) EXPECT_TRUE(t::finished(run / "cases" / t::case_id(i))) << i;
}

TEST(MpiExecutor, AnErrorOnRankZeroEndsEveryRank) {
  t::Scratch scratch("mpi_bad");
  const fs::path bad = scratch.dir / "bad.yaml";
  std::ofstream(bad) << "version: 1\nname: bad\nscene: {preset: quick, powdr: {count: 300}}\n"
                        "stages:\n  - simulate: {design: {type: list, cases: [{U: 100 mm/s}]}}\n";
  const t::Outcome mpi =
      t::run(t::under_mpirun(2, {"run", bad.string(), "--out", (scratch.dir / "run").string(), "--executor", "mpi"}));
  ASSERT_TRUE(mpi.exited) << mpi.describe();
  EXPECT_EQ(mpi.exit_code, 2) << mpi.describe();
  EXPECT_EQ(t::count(mpi.err, "scene.powdr: unknown key"), 1u) << "the error once, from rank 0:\n" << mpi.err;
  EXPECT_EQ(t::crash_marker(mpi.err), "") << mpi.err;
}

TEST(MpiExecutor, TheQuickstartsSimulateAndCharacteriseUnderTwoRanksGiveTheSerialMetricsCsv) {
  // workflows/quickstart.yaml itself (its scene and 3 x 3 design; figures off, train and map left
  // out), once serially and once under mpirun -n 2: metrics.csv byte for byte (deterministic mode;
  // the file holds no timings or host names).
  t::Scratch scratch("mpi_quickstart");
  std::string text = t::slurp(fs::path(SPREADMAP_SOURCE_DIR) / "workflows" / "quickstart.yaml");
  for (const std::string stage : {"  - simulate:\n", "  - characterise:\n"}) {
    const auto at = text.find(stage);
    ASSERT_NE(at, std::string::npos) << stage;
    text.insert(at + stage.size(), "      render: false\n");
  }
  const fs::path workflow = scratch.dir / "quickstart.yaml";
  std::ofstream(workflow) << text;
  const fs::path serial = scratch.dir / "serial", mpi = scratch.dir / "mpi";
  const t::Outcome s =
      t::run({{"run", workflow.string(), "--only", "simulate,characterise", "--out", serial.string(), "--jobs", "2"},
              {},
              {},
              {}});
  ASSERT_EQ(s.exit_code, 0) << s.describe();
  const t::Outcome m = t::run(t::under_mpirun(
      2, {"run", workflow.string(), "--only", "simulate,characterise", "--out", mpi.string(), "--executor", "mpi"}));
  ASSERT_TRUE(m.exited) << m.describe();
  ASSERT_EQ(m.exit_code, 0) << m.describe();
  const std::string a = t::slurp(serial / "metrics.csv"), b = t::slurp(mpi / "metrics.csv");
  EXPECT_EQ(std::count(a.begin(), a.end(), '\n'), 10) << "a header and the 9 cases:\n" << a;
  EXPECT_EQ(a, b);
  EXPECT_EQ(t::count(m.err, "characterise: 9 cases in metrics.csv"), 1u) << m.err;
}
