// Each stage on the user's own files, through the real binary: `spreadmap characterise` on a CSV
// whose layer has a closed form, `spreadmap train` on a CSV of an analytic response, `spreadmap map`
// and `spreadmap query` on the model it wrote.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <numbers>
#include <sstream>

#include "unit/surrogate_study_function.hpp"
#include "workflow/process.hpp"

namespace fs = std::filesystem;
namespace t = spreadmap::test;

namespace {

class StageCommands : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("spreadmap_stage_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) + "_" +
            std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    if (!HasFailure()) fs::remove_all(dir_);
  }
  t::Outcome spreadmap(std::vector<std::string> args) { return t::run({std::move(args), {}, {}, {}}); }
  fs::path dir_;
};

nlohmann::json json_of(const t::Outcome &r) {
  try {
    return nlohmann::json::parse(r.out);
  } catch (const std::exception &e) {
    ADD_FAILURE() << "not JSON: " << e.what() << "\n" << r.describe();
    return nullptr;
  }
}

}  // namespace

TEST_F(StageCommands, CharacteriseASphereAsJsonMatchesItsClosedForm) {
  // One sphere of radius R resting on the substrate in a 2 mm x 2 mm region: the volume under its
  // top surface is pi R^2 R + 2/3 pi R^3 = 5/3 pi R^3, its solid volume 4/3 pi R^3, its footprint pi R^2.
  const double R = 125e-6, area = 2e-3 * 2e-3, U = 0.1;
  std::ofstream(dir_ / "layer.csv") << "x,y,z,radius\n1e-3,1e-3," << R << "," << R << "\n";
  const auto r = spreadmap({"characterise", (dir_ / "layer.csv").string(), "--region", "0:2mm,0mm:2mm", "--grid", "2um",
                            "--U", "100 mm/s", "--format", "json"});
  ASSERT_EQ(r.exit_code, 0) << r.describe();
  const auto j = json_of(r);
  const double mean = 5.0 / 3.0 * std::numbers::pi * R * R * R / area;
  EXPECT_NEAR(j["mean_height"].get<double>(), mean, 2e-3 * mean);
  EXPECT_NEAR(j["vs"].get<double>(), j["mean_height"].get<double>() * U, 1e-12 * mean * U);
  EXPECT_NEAR(j["coverage"].get<double>(), std::numbers::pi * R * R / area, 2e-3 * std::numbers::pi * R * R / area);
  const double solid = 4.0 / 3.0 * std::numbers::pi * R * R * R / area;
  EXPECT_NEAR(j["solid_thickness"].get<double>(), solid, 1e-9 * solid);
  EXPECT_GT(j["rq"].get<double>(), 0.0);
}

TEST_F(StageCommands, CharacteriseAnEmptyRegionReportsUndefinedAsNull) {
  std::ofstream(dir_ / "layer.csv") << "x,y,z,radius\n1e-3,1e-3,125e-6,125e-6\n";
  const auto r =
      spreadmap({"characterise", (dir_ / "layer.csv").string(), "--region", "10mm:12mm,0:2mm", "--format", "json"});
  ASSERT_EQ(r.exit_code, 0) << r.describe();
  const auto j = json_of(r);
  EXPECT_EQ(j["mean_height"].get<double>(), 0.0);
  EXPECT_EQ(j["rq"].get<double>(), 0.0);
  EXPECT_EQ(j["coverage"].get<double>(), 0.0);
  EXPECT_TRUE(j["packing_fraction"].is_null()) << j.dump();
  EXPECT_FALSE(j.contains("vs") && !j["vs"].is_null()) << "no --U: V_s is not known";
  EXPECT_NE(r.err.find("warn"), std::string::npos) << "an empty region is worth a warning:\n" << r.err;
}

TEST_F(StageCommands, TrainMapAndQueryOnAUsersTable) {
  // The study's 5 x 9 design of the analytic stand-in (tests/unit/surrogate_study_function.hpp).
  const Eigen::MatrixXd x = t::study_grid(), y = t::study_outputs(x);
  {
    std::ofstream csv(dir_ / "data.csv");
    csv.precision(17);
    csv << "case,U,omega,Vs,Rq\n";
    for (Eigen::Index i = 0; i < x.rows(); ++i)
      csv << "c" << i << "," << x(i, 0) << "," << x(i, 1) << "," << y(i, 0) << "," << y(i, 1) << "\n";
  }
  const fs::path model_dir = dir_ / "gp";
  const auto trained = spreadmap({"train", (dir_ / "data.csv").string(), "--inputs", "U,omega", "--outputs", "vs,rq",
                                  "--model", "gp", "--out", model_dir.string(), "--format", "json", "--no-figures"});
  ASSERT_EQ(trained.exit_code, 0) << trained.describe();
  const auto report = json_of(trained);
  EXPECT_EQ(report["n_train"].get<int>(), 35);
  EXPECT_EQ(report["n_test"].get<int>(), 10);
  for (const char *o : {"vs", "rq"}) {
    EXPECT_LT(report["outputs"][o]["nrmse_test"].get<double>(), 1.0) << o;  // the gp bound of the surrogate tests
    EXPECT_GT(report["outputs"][o]["r_test"].get<double>(), 0.99) << o;
  }
  ASSERT_TRUE(fs::exists(model_dir / "model.json"));

  const fs::path map_dir = dir_ / "map";
  const auto mapped = spreadmap({"map", (model_dir / "model.json").string(), "--grid", "31x41", "--rq-max", "105um",
                                 "--out", map_dir.string(), "--no-figures"});
  ASSERT_EQ(mapped.exit_code, 0) << mapped.describe();
  std::ifstream map_csv(map_dir / "map.csv");
  std::size_t lines = 0;
  for (std::string line; std::getline(map_csv, line);) ++lines;
  EXPECT_EQ(lines, 1u + 31u * 41u);
  const auto optimum = nlohmann::json::parse(std::ifstream(map_dir / "optimum.json"));
  ASSERT_EQ(optimum["optima"].size(), 1u) << optimum.dump();
  const auto &best = optimum["optima"][0];
  ASSERT_TRUE(best["found"].get<bool>()) << best.dump();

  // The best setting for R_q <= 105 um on the analytic function itself, on the same grid: the map's
  // optimum must be that grid point or a neighbour.
  double best_vs = -1, best_u = 0, best_w = 0;
  for (int i = 0; i < 31; ++i)
    for (int k = 0; k < 41; ++k) {
      const double u = 0.04 + 0.06 * i / 30, w = -20 + 40.0 * k / 40;
      if (t::study_rq(u, w) <= 105e-6 && t::study_vs(u, w) > best_vs)
        best_vs = t::study_vs(u, w), best_u = u, best_w = w;
    }
  // grid steps: 2 mm/s in U, 1 rad/s in omega
  EXPECT_NEAR(best["inputs"]["U"].get<double>(), best_u, 0.06 / 30 * 1.01) << best.dump();
  EXPECT_NEAR(best["inputs"]["omega"].get<double>(), best_w, 1.0 * 1.01) << best.dump();
  const auto query = spreadmap({"query", (model_dir / "model.json").string(), "--best", "--rq-max", "105um"});
  ASSERT_EQ(query.exit_code, 0) << query.describe();
  const auto at = spreadmap({"query", (model_dir / "model.json").string(), "--at", "U=70mm/s,omega=-5rad/s"});
  ASSERT_EQ(at.exit_code, 0) << at.describe();
  EXPECT_NE(at.out.find("mm"), std::string::npos) << "predictions carry units:\n" << at.out;
  std::printf("analytic optimum U = %.4g m/s, omega = %.4g rad/s, V_s = %.4g m^2/s\nquery: %s", best_u, best_w, best_vs,
              query.out.c_str());
}

TEST_F(StageCommands, RenderAStateAtTheRequestedSize) {
  // A small heap as CSV; the PNG's header gives its size (big-endian width and height at bytes 16-23).
  {
    std::ofstream csv(dir_ / "heap.csv");
    csv << "x,y,z,radius\n";
    for (int i = 0; i < 40; ++i) csv << 0.3e-3 * (i % 10) << "," << 0.3e-3 * (i / 10) << ",1.25e-4,1.25e-4\n";
  }
  const fs::path png = dir_ / "heap.png";
  const auto r =
      spreadmap({"render", (dir_ / "heap.csv").string(), "--out", png.string(), "--width", "800", "--title", "heap"});
#ifndef SPREADMAP_TEST_FIGURES
  // a build without VTK says so and names the fix
  EXPECT_EQ(r.exit_code, 2) << r.describe();
  EXPECT_NE(r.err.find("this build has no VTK (configure with SPREADMAP_ENABLE_VTK=ON)"), std::string::npos) << r.err;
  return;
#endif
  ASSERT_EQ(r.exit_code, 0) << r.describe();
  std::ifstream in(png, std::ios::binary);
  std::string head(24, '\0');
  in.read(head.data(), 24);
  ASSERT_EQ(head.substr(1, 3), "PNG");
  auto be32 = [&](int at) {
    return (std::uint32_t(std::uint8_t(head[at])) << 24) | (std::uint32_t(std::uint8_t(head[at + 1])) << 16) |
           (std::uint32_t(std::uint8_t(head[at + 2])) << 8) | std::uint32_t(std::uint8_t(head[at + 3]));
  };
  EXPECT_EQ(be32(16), 800u);
  EXPECT_EQ(be32(20), 450u);  // the snapshot's 1600 x 900 aspect
  const auto bad = spreadmap({"render", (dir_ / "heap.csv").string(), "--out", png.string(), "--width", "20"});
  EXPECT_EQ(bad.exit_code, 2) << bad.describe();
  EXPECT_NE(bad.err.find("--width 20"), std::string::npos) << bad.err;
}

TEST_F(StageCommands, SimulateDrawsFramesOfTheSeriesAtTheStageWidth) {
  // render: {width, frames}: the snapshot and one frame per state of the series (3 snapshots and the
  // final state), all at the stage's width.
  std::ofstream(dir_ / "wf.yaml") << "version: 1\nname: frames\nscene:\n  preset: quick\n  domain: {length: 20 mm}\n"
                                     "  powder: {count: 200, heap_from: 6 mm, heap_to: 10 mm, settle_time: 0.02 s}\n"
                                     "  spreader: {use: roller, travel: 6 mm}\n  time: {snapshots: 3}\nstages:\n"
                                     "  - simulate:\n      render: {width: 640, frames: true}\n"
                                     "      design: {type: list, cases: [{U: 100 mm/s}]}\n";
  const auto r = spreadmap({"run", (dir_ / "wf.yaml").string(), "--out", (dir_ / "out").string()});
  ASSERT_EQ(r.exit_code, 0) << r.describe();
  const fs::path c = dir_ / "out" / "cases" / "c000";
  const auto record = nlohmann::json::parse(std::ifstream(c / "case.json"));
  ASSERT_EQ(record["series"].size(), 4u) << record.dump();
  double last_x = -1;
  for (const auto &e : record["series"]) {  // the roller moves forward from frame to frame
    EXPECT_GT(e["spreader"]["reference"][0].get<double>(), last_x);
    last_x = e["spreader"]["reference"][0];
  }
#ifndef SPREADMAP_TEST_FIGURES
  // a build without VTK says once that it draws nothing, and the case's numbers are all there
  EXPECT_NE(r.err.find("this build has no VTK"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(c / "snapshot.png"));
  return;
#endif
  for (const char *f : {"snapshot.png", "frames/frame_0000.png", "frames/frame_0003.png"}) {
    std::ifstream in(c / f, std::ios::binary);
    std::string head(24, '\0');
    ASSERT_TRUE(in.read(head.data(), 24)) << f;
    const std::uint32_t w = (std::uint32_t(std::uint8_t(head[18])) << 8) | std::uint8_t(head[19]);
    EXPECT_EQ(w, 640u) << f;
  }
  EXPECT_FALSE(fs::exists(c / "frames" / "frame_0004.png"));
}

TEST_F(StageCommands, CoarseGrainingScalesSpheresCountAndContactLengths) {
  // k = 2: spheres twice as large and 8 times fewer, overlap_max doubled, so the contact frequency
  // V_max / Delta_max halves and the automatic step doubles exactly.
  auto workflow = [&](const std::string &name, double k) {
    const fs::path wf = dir_ / (name + ".yaml");
    std::ofstream(wf) << "version: 1\nname: " << name << "\nscene:\n  preset: quick\n  domain: {length: 20 mm}\n"
                      << "  powder: {count: 400, heap_from: 6 mm, heap_to: 10 mm, settle_time: 0.01 s, coarse_grain: "
                      << k
                      << "}\n  spreader: {use: roller, travel: 2 mm}\nstages:\n  - simulate:\n      render: false\n"
                         "      design: {type: list, cases: [{U: 100 mm/s}]}\n";
    const auto r = spreadmap({"run", wf.string(), "--out", (dir_ / name).string()});
    EXPECT_EQ(r.exit_code, 0) << r.describe();
    return dir_ / name / "cases" / "c000";
  };
  const fs::path fine = workflow("fine", 1), coarse = workflow("coarse", 2);
  const auto scene = nlohmann::json::parse(std::ifstream(coarse / "scene.json"));
  EXPECT_DOUBLE_EQ(scene["powder"]["diameter"].get<double>(), 500e-6);
  EXPECT_EQ(scene["powder"]["count"].get<int>(), 50);
  EXPECT_DOUBLE_EQ(scene["contact"]["params"]["overlap_max"].get<double>(), 10e-6);  // the quick preset's 5 um x 2
  EXPECT_DOUBLE_EQ(scene["substrate"]["law"]["overlap_max"].get<double>(), 10e-6);
  EXPECT_DOUBLE_EQ(scene["contact"]["params"]["v_max"].get<double>(), 0.5);
  const auto c_fine = nlohmann::json::parse(std::ifstream(fine / "case.json"));
  const auto c_coarse = nlohmann::json::parse(std::ifstream(coarse / "case.json"));
  EXPECT_NEAR(c_coarse["dt"].get<double>(), 2 * c_fine["dt"].get<double>(), 1e-12 * c_fine["dt"].get<double>());
  EXPECT_EQ(c_coarse["particles_start"].get<int>(), 50);
}

TEST_F(StageCommands, TrainChoosesItsValidationBySizeAndSaysWhy) {
  const auto write = [&](const fs::path &csv, const Eigen::MatrixXd &x) {
    const Eigen::MatrixXd y = t::study_outputs(x);
    std::ofstream f(csv);
    f.precision(17);
    f << "U,omega,vs,rq\n";
    for (Eigen::Index i = 0; i < x.rows(); ++i)
      f << x(i, 0) << "," << x(i, 1) << "," << y(i, 0) << "," << y(i, 1) << "\n";
  };
  const auto train = [&](const fs::path &csv, std::vector<std::string> extra) {
    std::vector<std::string> args = {"train", csv.string(),           "--inputs", "U,omega", "--model",     "gp",
                                     "--out", (dir_ / "gp").string(), "--format", "json",    "--no-figures"};
    args.insert(args.end(), extra.begin(), extra.end());
    return spreadmap(args);
  };
  // 9 rows (the quickstart's 3 x 3): leave-one-out, no test rows, so no test R, and the JSON says why.
  write(dir_ / "nine.csv", t::study_grid(3, 3));
  const auto nine = train(dir_ / "nine.csv", {});
  ASSERT_EQ(nine.exit_code, 0) << nine.describe();
  const auto j = json_of(nine);
  EXPECT_EQ(j["split"], "loo");
  EXPECT_NE(j["split_reason"].get<std::string>().find("9 usable rows"), std::string::npos) << j.dump();
  EXPECT_EQ(j["n_test"].get<int>(), 0);
  EXPECT_EQ(j["cv_folds"].get<int>(), 9);
  for (const char *o : {"vs", "rq"}) {
    EXPECT_TRUE(j["outputs"][o]["r_test"].is_null()) << j.dump();
    EXPECT_GT(j["outputs"][o]["nrmse_cv"].get<double>(), 0.0) << o;
    EXPECT_GT(j["outputs"][o]["noise_std"].get<double>(), 0.0) << o;
    EXPECT_GT(j["outputs"][o]["signal_std"].get<double>(), j["outputs"][o]["noise_std"].get<double>()) << o;
  }
  EXPECT_EQ(j["outputs"]["rq"]["unit"], "m");
  ASSERT_FALSE(j["notes"].empty());
  {  // cv.csv holds the out-of-fold predictions the score was computed from
    std::ifstream cv(dir_ / "gp" / "cv.csv");
    std::string line;
    ASSERT_TRUE(std::getline(cv, line));
    EXPECT_EQ(line, "case,fold,vs_true,vs_cv,rq_true,rq_cv");
    std::vector<double> truth, predicted;
    while (std::getline(cv, line)) {
      std::vector<std::string> cells;
      std::stringstream row(line);
      for (std::string cell; std::getline(row, cell, ',');) cells.push_back(cell);
      ASSERT_EQ(cells.size(), 6u) << line;
      truth.push_back(std::stod(cells[4])), predicted.push_back(std::stod(cells[5]));
    }
    ASSERT_EQ(truth.size(), 9u);
    double sq = 0;
    for (std::size_t i = 0; i < 9; ++i) sq += (truth[i] - predicted[i]) * (truth[i] - predicted[i]) / 9;
    const double range = *std::max_element(truth.begin(), truth.end()) - *std::min_element(truth.begin(), truth.end());
    EXPECT_NEAR(100 * std::sqrt(sq) / range, j["outputs"]["rq"]["nrmse_cv"].get<double>(), 1e-9);
  }
  // Asked for the study's holdout on 9 rows: 7/2, and R on the 2 test rows is null, with a note.
  const auto held = train(dir_ / "nine.csv", {"--split", "holdout"});
  ASSERT_EQ(held.exit_code, 0) << held.describe();
  const auto h = json_of(held);
  EXPECT_EQ(h["n_test"].get<int>(), 2);
  EXPECT_TRUE(h["outputs"]["vs"]["r_test"].is_null()) << h.dump();
  EXPECT_TRUE(h["outputs"]["vs"]["nrmse_test"].is_number()) << h.dump();
  EXPECT_NE(h["notes"].dump().find("r_test is null: 2 rows"), std::string::npos) << h.dump();
  // 20 rows: 5-fold; kfold:K beyond the rows and an unknown split are refused with the forms allowed.
  write(dir_ / "twenty.csv", t::study_grid(4, 5));
  const auto twenty = train(dir_ / "twenty.csv", {});
  ASSERT_EQ(twenty.exit_code, 0) << twenty.describe();
  EXPECT_EQ(json_of(twenty)["split"], "kfold:5");
  const auto too_many = train(dir_ / "nine.csv", {"--split", "kfold:10"});
  EXPECT_EQ(too_many.exit_code, 2) << too_many.describe();
  EXPECT_NE(too_many.err.find("kfold:10 needs at least 10 usable rows"), std::string::npos) << too_many.err;
  const auto bad = train(dir_ / "nine.csv", {"--split", "kfolds"});
  EXPECT_EQ(bad.exit_code, 2) << bad.describe();
  EXPECT_NE(bad.err.find("kfold:K, loo or column:NAME"), std::string::npos) << bad.err;
}
