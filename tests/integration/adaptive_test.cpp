// design: adaptive in a workflow: the 3 x 3 space-filling start, then the GP's choices up to the
// budget; every case characterised; a second run recomputes nothing and chooses the same cases
// (the engine is deterministic, so the GP sees the same data). With two fidelities: the cheap
// cases' scenes carry the cheap keys, metrics.csv a fidelity input, and the map holds it at 1 (its
// --grid counts U and omega only).
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

TEST(AdaptiveDesign, TwoFidelitiesRunCheapCasesOnTheirSceneAndMapTheExpensiveOne) {
  const fs::path dir = fs::path(SPREADMAP_BINARY_DIR) / "test-runs" / "adaptive_fidelity";
  fs::remove_all(dir);
  const std::string wf = std::string(SPREADMAP_SOURCE_DIR) + "/tests/integration/data/adaptive_fidelity.yaml";
  std::string out;
  ASSERT_EQ(run("run " + wf + " --out " + dir.string(), out), 0) << out;

  const auto a = json_file(dir / "adaptive.json");
  EXPECT_EQ(a["cheap_cases"], 6) << "the budget of cheap cases: every setting";
  EXPECT_EQ(a["expensive_cases"], 5) << "the 4 corners, then one more (target 0.01 % is out of reach)";
  EXPECT_EQ(a["stop_reason"], "budget");
  EXPECT_NE(out.find("the map needed 5 expensive runs"), std::string::npos) << out;
  const auto manifest = json_file(dir / "manifest.json");
  ASSERT_EQ(manifest["design"]["variables"].size(), 3u);
  EXPECT_EQ(manifest["design"]["variables"][2]["name"], "fidelity");

  // cheap cases are c006..c011 (the row + 6 candidates), with the softer contacts
  const auto t = spreadmap::analysis::Table::read_csv((dir / "metrics.csv").string());
  ASSERT_EQ(t.rows(), 11u);
  const auto ids = t.texts("case");
  const auto fidelity = t.numbers("fidelity");
  std::size_t cheap = 0;
  for (std::size_t i = 0; i < t.rows(); ++i) {
    const auto scene = json_file(dir / "cases" / ids[i] / "scene.json");
    const bool is_cheap = fidelity[i] == 0.0;
    cheap += is_cheap;
    EXPECT_EQ(is_cheap, std::stoi(ids[i].substr(1)) >= 6) << ids[i];
    EXPECT_DOUBLE_EQ(scene["contact"]["params"]["overlap_max"].get<double>(), is_cheap ? 10e-6 : 5e-6) << ids[i];
    // no region.y in the workflow: each case measured across its own strip (half as wide when cheap)
    const double width = is_cheap ? 0.625e-3 : 1.25e-3;
    EXPECT_DOUBLE_EQ(scene["domain"]["width"].get<double>(), width) << ids[i];
    const auto region = json_file(dir / "cases" / ids[i] / "metrics.json")["region"];
    EXPECT_EQ(region["y"][0].get<double>(), 0.0) << ids[i];
    EXPECT_DOUBLE_EQ(region["y"][1].get<double>(), width) << ids[i];
  }
  EXPECT_EQ(cheap, 6u);

  // train's GP learnt one noise per fidelity (noise_by_input: 3), and keeps the groups in its state
  const auto gp = json_file(dir / "train" / "gp" / "model.json")["state"];
  EXPECT_EQ(gp["noise_groups"]["input"], 2);
  EXPECT_EQ(gp["noise_groups"]["values"], nlohmann::json({0.0, 1.0}));
  EXPECT_EQ(gp["theta"][0].size(), 6u) << "log(s^2), length scales of U, omega and the fidelity, two noises";

  // the model takes the fidelity as an input; the map holds it at 1 on the default 101 x 81 grid
  const auto map = spreadmap::analysis::Table::read_csv((dir / "map" / "map.csv").string());
  ASSERT_EQ(map.rows(), 101u * 81u);
  for (double f : map.numbers("fidelity")) ASSERT_EQ(f, 1.0);
  const auto optimum = json_file(dir / "map" / "optimum.json");
  for (const auto &o : optimum["optima"]) {
    if (!o.value("found", false)) continue;
    EXPECT_EQ(o["inputs"]["fidelity"], 1.0);
  }

  // --grid counts the mapped inputs, U and omega: the fidelity takes no count
  const fs::path coarse = dir / "map_21x11";
  const std::string model = (dir / "train" / "gp" / "model.json").string();
  ASSERT_EQ(run("map " + model + " --grid 21x11 --out " + coarse.string(), out), 0) << out;
  const auto small = spreadmap::analysis::Table::read_csv((coarse / "map.csv").string());
  EXPECT_EQ(small.rows(), 21u * 11u);
  EXPECT_NE(run("map " + model + " --grid 21x11x2 --out " + coarse.string(), out), 0);
  EXPECT_NE(out.find("the map has 2 inputs, the grid gives 3"), std::string::npos) << out;

  ASSERT_EQ(run("run " + wf + " --out " + dir.string(), out), 0) << out;
  EXPECT_NE(out.find("(0 run now, 11 finished before)"), std::string::npos) << out;
}

}  // namespace
