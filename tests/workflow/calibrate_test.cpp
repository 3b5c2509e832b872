// `spreadmap calibrate` through the real binary on a small drum: a calibration's runs are kept and a
// rerun reuses them, a scene file changed in place is run again, a measured angle no parameter in the
// box gives is refused naming the test and the fix, and bad calibration files are refused before
// anything runs, naming the file, the line, the key and the fix. The friction round trip on the full
// example drum is tests/integration/calibrate_round_trip_test.cpp (release only: minutes under asan).
#include <gtest/gtest.h>
#include <unistd.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>

#include "workflow/process.hpp"

namespace fs = std::filesystem;
namespace t = spreadmap::test;

namespace {

const fs::path data = fs::path(SPREADMAP_SOURCE_DIR) / "tests" / "workflow" / "data" / "calibrate";

nlohmann::json read_json(const fs::path &file) {
  std::ifstream in(file);
  return nlohmann::json::parse(in);
}

int occurrences(const std::string &text, const std::string &what) {
  int n = 0;
  for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

class Calibrate : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("spreadmap_calibrate_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    if (!HasFailure()) fs::remove_all(dir_);
  }
  // data/calibrate/small_drum_friction.yaml with `angle:` replaced, and its scene, copied into dir_
  // (the scene as given, or with its seed replaced).
  fs::path small_drum(const std::string &angle, const std::string &seed = "3") {
    std::ofstream(dir_ / "small_drum.yaml")
        << std::regex_replace(read(data / "small_drum.yaml"), std::regex("seed: 3"), "seed: " + seed);
    const fs::path file = dir_ / "small_drum_friction.yaml";
    std::ofstream(file) << std::regex_replace(read(data / "small_drum_friction.yaml"), std::regex("angle: [^,}]*"),
                                              "angle: " + angle);
    return file;
  }
  static std::string read(const fs::path &file) {
    std::ifstream in(file);
    return {std::istreambuf_iterator<char>(in), {}};
  }
  t::Outcome calibrate(const std::vector<std::string> &args) {
    std::vector<std::string> all = {"calibrate"};
    all.insert(all.end(), args.begin(), args.end());
    return t::run({all, {}, {{"OMP_NUM_THREADS", "2"}}, {}});
  }
  fs::path dir_;
};

TEST_F(Calibrate, RunsAreKeptUntilTheSceneChanges) {
  const fs::path out = dir_ / "out";
  const auto first = calibrate({small_drum("31 deg").string(), "--out", out.string()});
  ASSERT_EQ(first.exit_code, 0) << first.describe();
  const auto result = read_json(out / "calibration.json");
  EXPECT_EQ(result["runs"], 3);
  // The drum's angle grows with friction over the box (29-34 deg measured), so 31 deg lies inside it.
  const auto &range = result["tests"][0]["simulated_range_deg"];
  EXPECT_LT(range[0].get<double>(), 31.0);
  EXPECT_GT(range[1].get<double>(), 31.0);

  // Run again: every run is reused, the answer is the same.
  const auto again = calibrate({small_drum("31 deg").string(), "--out", out.string()});
  ASSERT_EQ(again.exit_code, 0) << again.describe();
  EXPECT_EQ(occurrences(again.out + again.err, "kept from before"), 3) << again.err;
  EXPECT_EQ(read_json(out / "calibration.json")["parameters"], result["parameters"]);

  // A scene file changed in place is not answered from the runs made with its old text.
  const auto changed = calibrate({small_drum("31 deg", "4").string(), "--out", out.string()});
  ASSERT_EQ(changed.exit_code, 0) << changed.describe();
  EXPECT_EQ(occurrences(changed.out + changed.err, "kept from before"), 0) << changed.err;

  // An angle no friction in the box gives is refused (from the kept runs), naming the test and the fix.
  const auto refused = calibrate({small_drum("80 deg", "4").string(), "--out", out.string()});
  EXPECT_EQ(refused.exit_code, 2) << refused.describe();
  EXPECT_EQ(occurrences(refused.out + refused.err, "kept from before"), 3) << refused.err;
  EXPECT_NE(refused.err.find("small_drum measured 80.00 deg"), std::string::npos) << refused.err;
  EXPECT_NE(refused.err.find("widen the ranges"), std::string::npos) << refused.err;
}

// The calibrate stage runs a calibration file in a workflow and, with apply: true, hands the
// calibrated friction to the later stages: the case's scene carries it, the substrate keeps its own.
TEST_F(Calibrate, StageAppliesTheCalibratedFrictionToTheLaterStages) {
  small_drum("31 deg");
  const fs::path workflow = dir_ / "wf.yaml";
  auto write_workflow = [&](const std::string &calibrate) {
    std::ofstream(workflow) << "version: 1\nname: calibrated\nscene:\n  preset: quick\n  threads: 1\n"
                               "  domain: {length: 20 mm}\n"
                               "  powder: {count: 300, heap_from: 6 mm, heap_to: 10 mm, settle_time: 0.02 s}\n"
                               "  spreader: {use: roller, travel: 8 mm}\n"
                               "  contact: {use: hooke_slider, friction: 0.9}\n"
                               "  substrate: {friction: 0.7}\n"
                               "stages:\n"
                            << calibrate
                            << "  - simulate:\n      render: false\n"
                               "      design: {type: list, cases: [{U: 100 mm/s}]}\n";
  };
  write_workflow("  - calibrate: {file: small_drum_friction.yaml, apply: true}\n");
  const fs::path out = dir_ / "out";
  const auto r = t::run({{"run", workflow.string(), "--out", out.string()}, {}, {{"OMP_NUM_THREADS", "2"}}, {}});
  ASSERT_EQ(r.exit_code, 0) << r.describe();
  const auto calibrated = read_json(out / "calibrate" / "calibration.json");
  const double best = calibrated["parameters"]["friction"]["best"];
  EXPECT_GT(best, 0.2);
  EXPECT_LT(best, 0.8);
  const auto scene = read_json(out / "cases" / "c000" / "scene.json");
  EXPECT_EQ(scene["contact"]["params"]["friction"].get<double>(), best);  // exactly the calibrated value
  EXPECT_EQ(scene["substrate"]["law"]["friction"].get<double>(), 0.7);

  // --only simulate after it: the calibrated value still applies (read back from calibrate/), and
  // the case is kept, not recomputed.
  const auto again = t::run(
      {{"run", workflow.string(), "--out", out.string(), "--only", "simulate"}, {}, {{"OMP_NUM_THREADS", "2"}}, {}});
  ASSERT_EQ(again.exit_code, 0) << again.describe();
  EXPECT_EQ(read_json(out / "cases" / "c000" / "scene.json")["contact"]["params"]["friction"].get<double>(), best);

  // apply to another law than the calibration's, and a misspelt key: refused
  write_workflow("  - calibrate: {file: small_drum_friction.yaml, apply: true}\n");
  {
    std::ifstream in(workflow);
    std::string text((std::istreambuf_iterator<char>(in)), {});
    text = std::regex_replace(text, std::regex("use: hooke_slider, friction: 0.9"), "use: hertz_mindlin");
    std::ofstream(workflow) << text;
  }
  const auto other_law = t::run({{"validate", workflow.string()}, {}, {}, {}});
  EXPECT_EQ(other_law.exit_code, 2) << other_law.describe();
  EXPECT_NE(other_law.err.find("calibrate.apply: the scene's contact law is hertz_mindlin"), std::string::npos)
      << other_law.err;
  write_workflow("  - calibrate: {file: small_drum_friction.yaml, aply: true}\n");
  const auto typo = t::run({{"validate", workflow.string()}, {}, {}, {}});
  EXPECT_EQ(typo.exit_code, 2) << typo.describe();
  EXPECT_NE(typo.err.find("wf.yaml:12:"), std::string::npos) << typo.err;
  EXPECT_NE(typo.err.find("did you mean 'apply'"), std::string::npos) << typo.err;
}

TEST_F(Calibrate, BadFilesAreRefusedBeforeAnythingRuns) {
  struct Case {
    std::string file, where, text;
  };
  const std::vector<Case> cases = {
      {"bad_parameter.yaml", "bad_parameter.yaml:3:", "did you mean 'friction'?"},
      {"bad_range.yaml", "bad_range.yaml:3:", "lo must be below hi"},
      {"missing_scene.yaml", "missing_scene.yaml:5:", "no such file"},
  };
  for (const auto &c : cases) {
    const auto r = calibrate({(data / c.file).string(), "--out", (dir_ / "out").string()});
    EXPECT_EQ(r.exit_code, 2) << c.file << ": " << r.describe();
    EXPECT_NE(r.err.find(c.where), std::string::npos) << c.file << ": " << r.err;
    EXPECT_NE(r.err.find(c.text), std::string::npos) << c.file << ": " << r.err;
    EXPECT_EQ(t::crash_marker(r.err), "") << r.err;
    EXPECT_FALSE(fs::exists(dir_ / "out" / "cases")) << c.file << ": ran before refusing";
  }
}

}  // namespace
