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
