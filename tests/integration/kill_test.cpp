// The kill/resume guarantee, whole: a small workflow (4 cases, characterise, train, map) is killed
// with SIGKILL just before its N-th rename (the moment a finished file is put in place), for every N
// up to the renames an undisturbed run makes; each time the same command run again finishes, and every
// result (each case's state and metrics, metrics.csv, the model, the map, the optimum) is byte for
// byte the undisturbed run's. The shim that kills is kill_at_rename.cpp, preloaded.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "integration/quickstart_run.hpp"

namespace {

namespace fs = std::filesystem;
using quickstart::shell;

std::string slurp(const fs::path &p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

fs::path workflow(const fs::path &dir) {
  fs::create_directories(dir);
  const fs::path wf = dir / "killed.yaml";
  std::ofstream(wf) << "version: 1\nname: killed\nscene:\n  preset: quick\n  threads: 1\n  domain: {length: 20 mm}\n"
                       "  powder: {count: 300, heap_from: 6 mm, heap_to: 10 mm, settle_time: 0.02 s}\n"
                       "  spreader: {use: roller, travel: 8 mm}\nstages:\n  - simulate:\n      render: false\n"
                       "      design: {type: full_factorial, U: [70 mm/s, 100 mm/s], omega: [-10 rad/s, 10 rad/s]}\n"
                       "  - characterise:\n      region: {x: [11 mm, 15 mm]}\n      render: false\n"
                       "  - train:\n      model: gp\n      render: false\n"
                       "  - map:\n      model: gp\n      grid: 21x11\n      rq_max: [120 um]\n      render: false\n";
  return wf;
}

// Every result a later user reads, by path relative to the run directory (the model less the path of
// the table it was trained on, which names its own run directory).
std::map<std::string, std::string> results(const fs::path &run) {
  std::map<std::string, std::string> out;
  for (const char *f : {"metrics.csv", "train/gp/cv.csv", "map/map.csv", "map/optimum.json"}) out[f] = slurp(run / f);
  auto model = nlohmann::json::parse(slurp(run / "train/gp/model.json"));
  model["training"].erase("source");
  out["train/gp/model.json"] = model.dump(1);
  for (const auto &c : fs::directory_iterator(run / "cases"))
    for (const char *f : {"state.vtp", "metrics.json"})
      out[fs::relative(c.path() / f, run).string()] = slurp(c.path() / f);
  return out;
}

std::string command(const fs::path &wf, const fs::path &run, const std::string &env = "") {
  return env + " " + quickstart::exe + " run " + wf.string() + " --jobs 2 --quiet --out " + run.string();
}

}  // namespace

TEST(KillAtEveryRename, EachKillResumesToTheUndisturbedRunsBytes) {
  const fs::path dir = fs::path(SPREADMAP_BINARY_DIR) / "test-runs" / "kill-at-rename";
  fs::remove_all(dir);
  const fs::path wf = workflow(dir), reference = dir / "reference";
  std::string out;
  ASSERT_EQ(shell(command(wf, reference, "LD_PRELOAD=" SPREADMAP_KILL_SHIM " SPREADMAP_COUNT_RENAMES=" +
                                             (dir / "renames").string()),
                  &out),
            0)
      << out;
  const long renames = std::stol(slurp(dir / "renames"));
  ASSERT_GT(renames, 40) << "a run puts dozens of files in place";
  const auto expected = results(reference);

  for (long n = 1; n <= renames; ++n) {
    const fs::path run = dir / ("killed_at_" + std::to_string(n));
    const int killed = shell(command(wf, run, "LD_PRELOAD=" SPREADMAP_KILL_SHIM " SPREADMAP_KILL_AT_RENAME=" +
                                                  std::to_string(n)),
                             &out);
    EXPECT_EQ(killed, 128 + SIGKILL) << "rename " << n << ": " << out;
    ASSERT_EQ(shell(command(wf, run), &out), 0) << "resuming after a kill at rename " << n << ":\n" << out;
    for (const auto &[file, bytes] : results(run))
      EXPECT_TRUE(bytes == expected.at(file)) << file << " differs from the undisturbed run's, killed at rename " << n;
    fs::remove_all(run);
  }
  fs::remove_all(dir);
}
