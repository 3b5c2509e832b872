// Nothing a run reads back is trusted blindly: a checkpoint damaged after it was written is named and
// the case starts again (to the very state an undisturbed run gives), a settled heap that changed is
// settled again, a state replaced since it was measured and metrics edited since they were written are
// measured again, and the temporaries of writes a killed run left behind are removed by the next run.
#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <thread>

#include "core/files.hpp"
#include "workflow/process.hpp"
#include "workflow/run_files.hpp"

namespace fs = std::filesystem;
namespace t = spreadmap::test;
using t::contains;
using t::slurp;

namespace {

// A tiny quick-preset scene (300 spheres, 8 mm of travel); `cases` is the design's list, and every
// workflow measures its layers.
fs::path workflow(const fs::path &dir, const std::string &cases, const std::string &time = "") {
  fs::create_directories(dir);
  const fs::path wf = dir / "wf.yaml";
  std::ofstream(wf) << "version: 1\nname: read_back\nscene:\n  preset: quick\n  threads: 1\n"
                       "  domain: {length: 20 mm}\n"
                       "  powder: {count: 300, heap_from: 6 mm, heap_to: 10 mm, settle_time: 0.02 s}\n"
                       "  spreader: {use: roller, travel: 8 mm}\n"
                    << time << "stages:\n  - simulate:\n      render: false\n      design: {type: list, cases: "
                    << cases << "}\n  - characterise:\n      region: {x: [11 mm, 15 mm]}\n      render: false\n";
  return wf;
}

}  // namespace

TEST(ReadBack, ADamagedCheckpointIsNamedAndTheCaseStartsAgainToTheSameState) {
  const fs::path dir = t::fresh_run_directory("spreadmap_read_back_checkpoint");
  // slow enough (5 mm/s: seconds of spreading) that a checkpoint is written a second into the pass
  const fs::path wf = workflow(dir, "[{U: 5 mm/s}]", "  time: {checkpoint_interval: 1 s}\n");
  const t::Command reference{{"run", wf.string(), "--only", "simulate", "--out", (dir / "reference").string()}, {}, {}, {}};
  ASSERT_EQ(t::run(reference).exit_code, 0);
  const fs::path run = dir / "run", c0 = run / "cases" / "c000";
  const t::Command command{{"run", wf.string(), "--only", "simulate", "--out", run.string()}, {}, {}, {}};
  {
    t::Child child(command);  // killed as a crash would: no chance to checkpoint again on the way out
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::minutes(5);
    while (child.running() && !fs::exists(c0 / "checkpoint.hash") && std::chrono::steady_clock::now() < deadline)
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    ASSERT_TRUE(child.running()) << "the case ended before a checkpoint: " << child.wait().describe();
    child.signal(SIGKILL);
    child.wait();
  }
  ASSERT_TRUE(fs::exists(c0 / "checkpoint.bin"));
  ASSERT_FALSE(fs::exists(c0 / "case.json"));
  std::string bytes = slurp(c0 / "checkpoint.bin");
  bytes[bytes.size() / 2] = static_cast<char>(~bytes[bytes.size() / 2]);  // one byte, in the particles
  std::ofstream(c0 / "checkpoint.bin", std::ios::binary | std::ios::trunc) << bytes;

  const t::Outcome resumed = t::run(command);
  ASSERT_EQ(resumed.exit_code, 0) << resumed.describe();
  EXPECT_EQ(t::crash_marker(resumed.err), "") << resumed.describe();
  EXPECT_TRUE(contains(resumed.err, "its checkpoint cannot be resumed")) << resumed.err;
  EXPECT_TRUE(contains(resumed.err, (c0 / "checkpoint.bin").string() + ": damaged")) << resumed.err;
  EXPECT_FALSE(contains(resumed.err, "resuming from its checkpoint")) << resumed.err;
  EXPECT_EQ(slurp(c0 / "state.vtp"), slurp(dir / "reference" / "cases" / "c000" / "state.vtp"))
      << "started again, the case gives the undisturbed run's state bit for bit";
  fs::remove_all(dir);
}

TEST(ReadBack, AChangedHeapIsSettledAgainAndAReplacedStateIsMeasuredAgain) {
  const fs::path dir = t::fresh_run_directory("spreadmap_read_back_stale");
  const fs::path run = dir / "run", c0 = run / "cases" / "c000", c1 = run / "cases" / "c001";
  const t::Command command{{"run", workflow(dir, "[{U: 100 mm/s}, {U: 90 mm/s}]").string(), "--out", run.string()},
                           {}, {}, {}};
  ASSERT_EQ(t::run(command).exit_code, 0);
  const std::string state0 = slurp(c0 / "state.vtp");

  // 1. the cached heap is changed, and the first case must run again: it settles the heap anew and
  //    gives the same state (the heap it was made from is the one the scene makes)
  fs::path heap;
  for (const auto &e : fs::directory_iterator(run / "heaps"))
    if (e.path().extension() == ".vtp") heap = e.path();
  ASSERT_FALSE(heap.empty());
  std::string text = slurp(heap);
  text.replace(text.find("<VTKFile"), 8, "<VTKFile ");
  std::ofstream(heap, std::ios::binary | std::ios::trunc) << text;
  fs::remove(c0 / "case.json");
  const t::Outcome resettled = t::run(command);
  ASSERT_EQ(resettled.exit_code, 0) << resettled.describe();
  EXPECT_TRUE(contains(resettled.err, heap.string() + " changed since it was written")) << resettled.err;
  EXPECT_EQ(slurp(c0 / "state.vtp"), state0);
  EXPECT_TRUE(contains(resettled.err, "2 cases in metrics.csv (0 evaluated, 2 up to date)"))
      << "the same state: its metrics stand\n" << resettled.err;

  // 2. the first case's state is replaced (as a re-simulation from another heap would) and its record
  //    with it: its metrics are measured again, never kept for a state that no longer is
  const std::string state1 = slurp(c1 / "state.vtp");
  std::ofstream(c0 / "state.vtp", std::ios::binary | std::ios::trunc) << state1;
  auto record = nlohmann::json::parse(slurp(c0 / "case.json"));
  record["state_bytes"] = state1.size();
  record["state_hash"] = spreadmap::stable_hash(state1);
  std::ofstream(c0 / "case.json", std::ios::trunc) << record.dump(2);
  const t::Outcome measured = t::run(command);
  ASSERT_EQ(measured.exit_code, 0) << measured.describe();
  EXPECT_TRUE(contains(measured.err, "2 cases, 0 to run, 2 finished already")) << measured.err;
  EXPECT_TRUE(contains(measured.err, "2 cases in metrics.csv (1 evaluated, 1 up to date)")) << measured.err;
  const auto height = t::csv_columns(run / "metrics.csv").at("mean_height");
  ASSERT_EQ(height.size(), 2u);
  EXPECT_EQ(height[0], height[1]) << "c000's row describes the state it now holds";

  // 3. a measured value edited in metrics.json (still valid JSON) is measured again, not believed
  auto doc = nlohmann::json::parse(slurp(c1 / "metrics.json"));
  const double true_height = doc["metrics"]["mean_height"].get<double>();
  doc["metrics"]["mean_height"] = 2 * true_height;
  std::ofstream(c1 / "metrics.json", std::ios::trunc) << doc.dump(2);
  const t::Outcome remeasured = t::run(command);
  ASSERT_EQ(remeasured.exit_code, 0) << remeasured.describe();
  EXPECT_TRUE(contains(remeasured.err, (c1 / "metrics.json").string() + " changed since it was written"))
      << remeasured.err;
  EXPECT_TRUE(contains(remeasured.err, "2 cases in metrics.csv (1 evaluated, 1 up to date)")) << remeasured.err;
  EXPECT_EQ(nlohmann::json::parse(slurp(c1 / "metrics.json"))["metrics"]["mean_height"].get<double>(), true_height);
  fs::remove_all(dir);
}

TEST(ReadBack, TemporariesOfAKilledWriteAreRemovedByTheNextRun) {
  const fs::path dir = t::fresh_run_directory("spreadmap_read_back_temporaries");
  const fs::path run = dir / "run";
  const t::Command command{{"run", workflow(dir, "[{U: 100 mm/s}]").string(), "--out", run.string()}, {}, {}, {}};
  ASSERT_EQ(t::run(command).exit_code, 0);
  // a writer pid beyond any pid_max: no such process runs
  const fs::path stale = run / "cases" / "c000" / ".state.vtp.tmp-1073741824-0-1234abcd.vtp";
  const fs::path recent = run / ".metrics.csv.tmp-1073741824-1-1234abcd.csv";
  std::ofstream(stale) << "half a file";
  std::ofstream(recent) << "written a moment ago";
  fs::last_write_time(stale, fs::file_time_type::clock::now() - std::chrono::minutes(5));
  const t::Outcome again = t::run(command);
  ASSERT_EQ(again.exit_code, 0) << again.describe();
  EXPECT_FALSE(fs::exists(stale));
  EXPECT_TRUE(fs::exists(recent)) << "a temporary under a minute old may be a live writer's on another host";
  EXPECT_TRUE(contains(again.err, "removed 1 temporary files of writes a killed run left unfinished")) << again.err;
  fs::remove_all(dir);
}

// Killed after a case's files and before the manifest recorded its outcome (its snapshot was being
// drawn, say): the next run finds the case finished and takes its timing from the case's timing.json.
TEST(ReadBack, ACaseTheManifestNeverHeardOfKeepsItsTiming) {
  const fs::path dir = t::fresh_run_directory("spreadmap_read_back_timing");
  const fs::path run = dir / "run";
  const t::Command command{{"run", workflow(dir, "[{U: 100 mm/s}, {U: 90 mm/s}]").string(), "--out", run.string()},
                           {}, {}, {}};
  ASSERT_EQ(t::run(command).exit_code, 0);
  const auto timing = t::json_file(run / "cases" / "c000" / "timing.json");
  auto manifest = t::json_file(run / "manifest.json");
  for (auto &c : manifest["cases"])
    if (c["id"] == "c000")
      for (const char *k : {"start", "end", "wall_seconds", "status", "rank", "host"}) c.erase(k);
  std::ofstream(run / "manifest.json", std::ios::trunc) << manifest.dump(2);
  const t::Outcome again = t::run(command);
  ASSERT_EQ(again.exit_code, 0) << again.describe();
  EXPECT_TRUE(contains(again.err, "2 cases, 0 to run, 2 finished already")) << again.err;
  const auto after = t::json_file(run / "manifest.json");  // (named: a range-for over a temporary's member dangles)
  for (const auto &c : after["cases"])
    if (c["id"] == "c000") {
      EXPECT_EQ(c.value("status", ""), "done");
      EXPECT_EQ(c.value("start", ""), timing["start"].get<std::string>());
      EXPECT_EQ(c.value("end", ""), timing["end"].get<std::string>());
      EXPECT_EQ(c.value("wall_seconds", -1.0), timing["wall_seconds"].get<double>());
    }
  fs::remove_all(dir);
}
