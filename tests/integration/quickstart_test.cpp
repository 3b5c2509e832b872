// Checks what each stage of the quickstart run must leave in its run directory (quickstart_run.hpp).
// Exit codes and files are checked; so is the physics the quickstart must show at least: a faster
// spreader spreads more powder per second.
#include <cstdio>
#include <fstream>

#include "integration/quickstart_run.hpp"

namespace {

using namespace quickstart;

TEST_F(Quickstart, RunsAllFourStages) {
  ASSERT_EQ(status_, 0) << log_;
  const auto m = json_file(run_dir / "manifest.json");
  ASSERT_EQ(m["cases"].size(), 9u);
  for (const auto &c : m["cases"]) EXPECT_EQ(c.value("status", ""), "done") << c.dump();
  for (const char *s : {"simulate", "characterise", "train", "map"}) EXPECT_TRUE(m["stages"].contains(s)) << s;
}

TEST_F(Quickstart, MetricsCsvHasVsAndRqForEveryCaseWithUnits) {
  ASSERT_EQ(status_, 0) << log_;
  const Table t = Table::read_csv((run_dir / "metrics.csv").string());
  ASSERT_EQ(t.rows(), 9u);
  const auto u = t.numbers("U"), vs = t.numbers("vs"), rq = t.numbers("rq"), h = t.numbers("mean_height");
  for (std::size_t i = 0; i < t.rows(); ++i) {
    EXPECT_GT(rq[i], 0.0);
    EXPECT_NEAR(vs[i], h[i] * u[i], 1e-12 * vs[i]) << "V_s is mean height x U (the study's definition)";
    // a layer spread through a 0.5 mm gap: between a tenth of a diameter and the gap plus a diameter
    EXPECT_GT(h[i], 25e-6);
    EXPECT_LT(h[i], 0.5e-3 + 250e-6);
  }
  const auto units = json_file(run_dir / "metrics.units.json");
  EXPECT_EQ(units["vs"], "m^2/s");
  EXPECT_EQ(units["rq"], "m");
  EXPECT_EQ(units["U"], "m/s");
  EXPECT_EQ(units["omega"], "rad/s");
}

TEST_F(Quickstart, FasterSpreaderSpreadsMorePowderPerSecond) {
  ASSERT_EQ(status_, 0) << log_;
  // The study's first-order result: V_s grows with U at every rotation (the layer thins much less
  // than U grows).
  const Table t = Table::read_csv((run_dir / "metrics.csv").string());
  const auto u = t.numbers("U"), w = t.numbers("omega"), vs = t.numbers("vs");
  for (std::size_t i = 0; i < t.rows(); ++i)
    for (std::size_t j = 0; j < t.rows(); ++j)
      if (w[i] == w[j] && u[j] > u[i]) {
        EXPECT_GT(vs[j], vs[i]) << "omega " << w[i] << ": U " << u[i] << " -> " << u[j];
      }
}

TEST_F(Quickstart, EveryCaseHasItsStateHeightMapAndMetrics) {
  ASSERT_EQ(status_, 0) << log_;
  for (int i = 0; i < 9; ++i) {
    char id[16];  // room for any int, so that the compiler sees no truncation
    std::snprintf(id, sizeof id, "c%03d", i);
    const fs::path d = run_dir / "cases" / id;
    for (const char *f : {"state.vtp", "scene.json", "case.json", "metrics.json", "heightmap.vti"})
      EXPECT_TRUE(fs::exists(d / f)) << (d / f);
    std::ifstream vtp(d / "state.vtp");
    std::string head((std::istreambuf_iterator<char>(vtp)), {});
    EXPECT_NE(head.find("<VTKFile type=\"PolyData\""), std::string::npos);
    EXPECT_NE(head.find("</VTKFile>"), std::string::npos) << "a whole file, never a partial one";
  }
}

TEST_F(Quickstart, TrainWritesModelsReportsAndTheMap) {
  ASSERT_EQ(status_, 0) << log_;
  for (const char *model : {"bpnn", "gp"}) {
    const fs::path d = run_dir / "train" / model;
    for (const char *f : {"model.json", "report.json", "report.csv", "parity.csv", "data.csv"})
      EXPECT_TRUE(fs::exists(d / f)) << (d / f);
    const auto report = json_file(d / "report.json");
    ASSERT_EQ(report["outputs"].size(), 2u);
    EXPECT_EQ(report["n_train"].get<int>() + report["n_test"].get<int>(), 9);
  }
  const Table map = Table::read_csv((run_dir / "map" / "map.csv").string());
  EXPECT_EQ(map.rows(), 101u * 81u);
  EXPECT_TRUE(map.has_column("rq_std")) << "the gp map carries its uncertainty";
  const auto opt = json_file(run_dir / "map" / "optimum.json");
  ASSERT_EQ(opt["optima"].size(), 2u);
  EXPECT_TRUE(fs::exists(run_dir / "map" / "frontier.csv"));
}

TEST_F(Quickstart, TheOptimumStatesItsProbabilityAndTheUntrustedRqMapIsMarked) {
  ASSERT_EQ(status_, 0) << log_;
  const auto opt = json_file(run_dir / "map" / "optimum.json");
  EXPECT_EQ(opt["confidence"].get<double>(), 0.9) << "the default confidence";
  for (const auto &o : opt["optima"]) {
    if (!o["found"].get<bool>()) continue;
    EXPECT_GE(o["probability"].get<double>(), 0.9) << o.dump();
    EXPECT_LE(o["rq"].get<double>(), o["rq_max"].get<double>()) << "inside the mean rule's feasible set";
    EXPECT_EQ(o["rq_std_source"], "model");
    EXPECT_EQ(o["rests_on_untrusted"], nlohmann::json::array({"rq"}));
  }
  // 9 cases at quick fidelity: R_q's trend is lost in its scatter (leave-one-out Q^2 < 0), V_s's is not
  EXPECT_EQ(opt["trust"]["rq"]["verdict"], "untrusted") << opt["trust"].dump();
  EXPECT_LT(opt["trust"]["rq"]["q2_cv"].get<double>(), 0.5);
  EXPECT_EQ(opt["trust"]["vs"]["verdict"], "trusted") << opt["trust"].dump();
  EXPECT_GT(opt["trust"]["vs"]["q2_cv"].get<double>(), 0.9);
  EXPECT_NE(log_.find("the rq map is NOT TRUSTED"), std::string::npos) << log_;
  // confidence 0.5 is the mean rule: the predicted R_q at most the target, nothing more asked
  std::string out;
  ASSERT_EQ(run("query " + (run_dir / "train" / "gp" / "model.json").string() +
                    " --best --rq-max 105um --confidence 0.5",
                &out),
            0)
      << out;
  EXPECT_NE(out.find("(confidence 0.50)"), std::string::npos) << out;
  EXPECT_NE(out.find("P(R_q <= 105 um) = "), std::string::npos) << out;
  EXPECT_NE(out.find("R_q map NOT TRUSTED"), std::string::npos) << out;
  EXPECT_NE(run("query " + (run_dir / "train" / "gp" / "model.json").string() + " --best --rq-max 105um --confidence 1",
                &out),
            0);
  EXPECT_NE(out.find("--confidence: 1 is outside [0.5, 1)"), std::string::npos) << out;
}

TEST_F(Quickstart, QueryGivesTheBestSettingForARoughness) {
  ASSERT_EQ(status_, 0) << log_;
  std::string out;
  ASSERT_EQ(run("query " + (run_dir / "train" / "gp" / "model.json").string() + " --best --rq-max 110um", &out), 0)
      << out;
  EXPECT_NE(out.find("U = "), std::string::npos) << out;
  EXPECT_NE(out.find("mm^2/s"), std::string::npos) << out;
  ASSERT_EQ(run("query " + (run_dir / "train" / "gp" / "model.json").string() + " --at U=70mm/s,omega=0rad/s", &out), 0)
      << out;
  EXPECT_NE(out.find("+-"), std::string::npos) << "gp predictions come with their standard deviation: " << out;
}

#ifdef SPREADMAP_TEST_FIGURES
TEST_F(Quickstart, DrawsSnapshotHeightMapSurfacesParityAndMap) {
  ASSERT_EQ(status_, 0) << log_;
  std::vector<fs::path> pngs = {run_dir / "cases/c000/snapshot.png", run_dir / "cases/c000/heightmap.png",
                                run_dir / "train/bpnn/parity.png",   run_dir / "map/map.png",
                                run_dir / "map/surface_vs.png",      run_dir / "map/surface_rq.png"};
  for (const auto &p : pngs) {
    ASSERT_TRUE(fs::exists(p)) << p;
    std::ifstream in(p, std::ios::binary);
    unsigned char sig[8] = {};
    in.read(reinterpret_cast<char *>(sig), 8);
    EXPECT_EQ(sig[1], 'P');
    EXPECT_EQ(sig[2], 'N');
    EXPECT_GT(fs::file_size(p), 20000u) << p << " looks blank";
  }
}
#endif

#ifdef SPREADMAP_TEST_FIGURES
// A figure lost to a kill or a full disk is drawn again by the next run: a case's snapshot by the
// simulate stage (the case itself is not run again), a height map with its case's metrics.
TEST_F(Quickstart, AMissingOrTornFigureIsDrawnAgain) {
  ASSERT_EQ(status_, 0) << log_;
  const RunLock lock;
  const fs::path snapshot = run_dir / "cases/c002/snapshot.png", heightmap = run_dir / "cases/c003/heightmap.png";
  const auto state = fs::last_write_time(run_dir / "cases/c002/state.vtp");
  fs::remove(snapshot);
  fs::resize_file(heightmap, fs::file_size(heightmap) / 2);
  std::string out;
  ASSERT_EQ(run("run " + std::string(SPREADMAP_SOURCE_DIR) +
                    "/workflows/quickstart.yaml --only simulate,characterise --out " + run_dir.string(),
                &out),
            0)
      << out;
  EXPECT_NE(out.find("c002: snapshot.png is missing or torn; drawing it again"), std::string::npos) << out;
  EXPECT_NE(out.find("0 to run, 9 finished already"), std::string::npos) << out;
  EXPECT_NE(out.find("9 cases in metrics.csv (1 evaluated, 8 up to date)"), std::string::npos) << out;
  EXPECT_EQ(fs::last_write_time(run_dir / "cases/c002/state.vtp"), state);
  for (const auto &png : {snapshot, heightmap}) {
    std::ifstream in(png, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), {});
    ASSERT_GT(bytes.size(), 20000u) << png;
    EXPECT_EQ(bytes.substr(bytes.size() - 8, 4), "IEND") << png << " is whole again";
  }
}
#endif

TEST_F(Quickstart, ASecondRunRecomputesNothing) {
  ASSERT_EQ(status_, 0) << log_;
  const auto before = fs::last_write_time(run_dir / "cases/c004/state.vtp");
  std::string out;
  const RunLock lock;
  ASSERT_EQ(run("run " + std::string(SPREADMAP_SOURCE_DIR) +
                    "/workflows/quickstart.yaml --only simulate,characterise --out " + run_dir.string(),
                &out),
            0)
      << out;
  EXPECT_NE(out.find("0 to run, 9 finished already"), std::string::npos) << out;
  EXPECT_NE(out.find("9 up to date"), std::string::npos) << out;
  EXPECT_EQ(fs::last_write_time(run_dir / "cases/c004/state.vtp"), before);
}

}  // namespace
