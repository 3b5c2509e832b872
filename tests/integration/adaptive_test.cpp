// design: adaptive in a workflow: the 3 x 3 space-filling start, then the GP's choices up to the
// budget; every case characterised; a second run recomputes nothing and chooses the same cases
// (the engine is deterministic, so the GP sees the same data).
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <string>

#include "analysis/table.hpp"

namespace fs = std::filesystem;

namespace {

int run(const std::string &args, std::string &out) {
  const std::string cmd = std::string(SPREADMAP_BINARY_DIR) + "/bin/spreadmap " + args + " 2>&1";
  FILE *p = popen(cmd.c_str(), "r");
  char buf[4096];
  out.clear();
  while (p && fgets(buf, sizeof buf, p)) out += buf;
  const int status = p ? pclose(p) : -1;
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

nlohmann::json json_file(const fs::path &p) {
  std::ifstream in(p);
  return nlohmann::json::parse(in);
}

TEST(AdaptiveDesign, StartsSpaceFillingThenSpendsTheBudgetAndResumesWithoutRecomputing) {
  const fs::path dir = fs::path(SPREADMAP_BINARY_DIR) / "test-runs" / "adaptive";
  fs::remove_all(dir);
  const std::string wf = std::string(SPREADMAP_SOURCE_DIR) + "/tests/integration/data/adaptive.yaml";
  std::string out;
  ASSERT_EQ(run("run " + wf + " --out " + dir.string(), out), 0) << out;

  const auto a = json_file(dir / "adaptive.json");
  ASSERT_EQ(a["cases"].size(), 11u) << "target 0.01 % is out of reach: the budget of 11 decides";
  EXPECT_EQ(a["stop_reason"], "budget");
  std::set<std::string> ids;
  for (const auto &c : a["cases"]) ids.insert(c.get<std::string>());
  EXPECT_EQ(ids.size(), 11u) << "no setting simulated twice";
  // the 3 x 3 lattice of the 5 x 5 grid (rows U-major: id = 5 iU + iW) comes first
  const std::set<std::string> lattice = {"c000", "c002", "c004", "c010", "c012", "c014", "c020", "c022", "c024"};
  for (std::size_t i = 0; i < 9; ++i) EXPECT_TRUE(lattice.count(a["cases"][i].get<std::string>())) << a["cases"][i];
  ASSERT_EQ(a["history"].size(), 3u);  // fits after 9, 10 and 11 cases

  const auto t = spreadmap::analysis::Table::read_csv((dir / "metrics.csv").string());
  ASSERT_EQ(t.rows(), 11u);
  for (double vs : t.numbers("vs")) EXPECT_GT(vs, 0.0);

  ASSERT_EQ(run("run " + wf + " --out " + dir.string(), out), 0) << out;
  EXPECT_NE(out.find("(0 run now, 11 finished before)"), std::string::npos) << out;
  EXPECT_EQ(json_file(dir / "adaptive.json")["cases"], a["cases"]);
}

}  // namespace
