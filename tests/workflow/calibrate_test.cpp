// `spreadmap calibrate` through the real binary: a round trip on the example drum (the angle the
// tool gives at a known friction, then the friction calibrated from that angle, which must hold the
// known one in its 68 % set), a rerun that reuses every finished run, and bad calibration files
// refused before anything runs, naming the file, the line, the key and the fix.
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
  // data/calibrate/<name> copied beside the example scenes' path it names, with `angle:` replaced.
  fs::path with_angle(const std::string &name, const std::string &angle) {
    std::ifstream in(data / name);
    std::string text((std::istreambuf_iterator<char>(in)), {});
    text = std::regex_replace(text, std::regex("angle: [^,}]*"), "angle: " + angle);
    text = std::regex_replace(text, std::regex("scene: \\.\\./\\.\\./\\.\\./\\.\\./"),
                              "scene: " + fs::path(SPREADMAP_SOURCE_DIR).string() + "/");
    const fs::path file = dir_ / name;
    std::ofstream(file) << text;
    return file;
  }
  t::Outcome calibrate(const std::vector<std::string> &args) {
    std::vector<std::string> all = {"calibrate"};
    all.insert(all.end(), args.begin(), args.end());
    return t::run({all, {}, {{"OMP_NUM_THREADS", "2"}}, {}});
  }
  fs::path dir_;
};

TEST_F(Calibrate, DrumAngleGivesBackTheFrictionThatMadeIt) {
  const fs::path out = dir_ / "out";
  const fs::path file = with_angle("drum_friction.yaml", "30 deg");
  const auto at = calibrate({file.string(), "--out", out.string(), "--at", "friction=0.4"});
  ASSERT_EQ(at.exit_code, 0) << at.describe();
  const double angle = read_json(out / "at.json")["tests"][0]["angle_deg"];
  std::printf("drum angle at friction 0.4 (not a design point): %.2f deg\n", angle);

  const fs::path measured = with_angle("drum_friction.yaml", std::to_string(angle) + " deg");
  const auto run = calibrate({measured.string(), "--out", out.string()});
  ASSERT_EQ(run.exit_code, 0) << run.describe();
  const auto result = read_json(out / "calibration.json");
  const auto &mu = result["parameters"]["friction"];
  std::printf("friction %.3f (68 %% set %.3f to %.3f); surrogate leave-one-out %.2f deg\n", mu["best"].get<double>(),
              mu["lower"].get<double>(), mu["upper"].get<double>(),
              result["tests"][0]["surrogate_loo_rmse_deg"].get<double>());
  EXPECT_LE(mu["lower"].get<double>(), 0.4);
  EXPECT_GE(mu["upper"].get<double>(), 0.4);
  // ... and the drum does identify it: a set inside the box, well narrower than it (0.29-0.52 measured).
  EXPECT_TRUE(mu["bounded"].get<bool>());
  EXPECT_LT(mu["upper"].get<double>() - mu["lower"].get<double>(), 0.4);
  EXPECT_EQ(result["runs"], 3);

  // Run again: every run is reused, the answer is the same.
  const auto again = calibrate({measured.string(), "--out", out.string()});
  ASSERT_EQ(again.exit_code, 0) << again.describe();
  EXPECT_NE((again.out + again.err).find("kept from before"), std::string::npos);
  EXPECT_EQ(read_json(out / "calibration.json")["parameters"], result["parameters"]);

  // A scene file changed in place is not answered from the runs made with its old text.
  const fs::path scene = dir_ / "drum.yaml";
  auto write_scene = [&](const std::string &seed) {
    std::ifstream in(fs::path(SPREADMAP_SOURCE_DIR) / "examples" / "scenes" / "rotating_drum.yaml");
    const std::string text((std::istreambuf_iterator<char>(in)), {});
    std::ofstream(scene) << std::regex_replace(text, std::regex("seed: 3"), "seed: " + seed);
  };
  {
    std::ifstream in(measured);
    const std::string text((std::istreambuf_iterator<char>(in)), {});
    std::ofstream(measured) << std::regex_replace(text, std::regex("scene: [^,]*"), "scene: " + scene.string());
  }
  write_scene("3");
  ASSERT_EQ(calibrate({measured.string(), "--out", out.string()}).exit_code, 0);
  write_scene("4");
  const auto changed = calibrate({measured.string(), "--out", out.string()});
  ASSERT_EQ(changed.exit_code, 0) << changed.describe();
  EXPECT_EQ((changed.out + changed.err).find("kept from before"), std::string::npos) << changed.err;

  // An angle no friction in the box gives is refused, naming the test and the fix.
  const fs::path steep = with_angle("drum_friction.yaml", "80 deg");
  const auto refused = calibrate({steep.string(), "--out", out.string()});
  EXPECT_EQ(refused.exit_code, 2) << refused.describe();
  EXPECT_NE(refused.err.find("rotating_drum measured 80.00 deg"), std::string::npos) << refused.err;
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
