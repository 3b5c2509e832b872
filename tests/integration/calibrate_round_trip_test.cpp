// The calibration round trip on the example drum (examples/scenes/rotating_drum.yaml) through the real
// binary: the angle the tool gives at a known friction that is not a design point, then the friction
// calibrated from that angle, which must hold the known one in its 68 % set and bound it well inside
// the box. Four drum runs, about 25 s in release; the sanitizer builds run the small drum's
// tests/workflow/calibrate_test.cpp instead.
#include <gtest/gtest.h>
#include <unistd.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>

#include "workflow/process.hpp"

namespace fs = std::filesystem;
namespace t = spreadmap::test;

namespace {

nlohmann::json read_json(const fs::path &file) {
  std::ifstream in(file);
  return nlohmann::json::parse(in);
}

class CalibrateRoundTrip : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("spreadmap_round_trip_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    if (!HasFailure()) fs::remove_all(dir_);
  }
  // tests/workflow/data/calibrate/drum_friction.yaml with `angle:` replaced and its scene's path made
  // absolute, written into dir_.
  fs::path with_angle(const std::string &angle) {
    const fs::path source = fs::path(SPREADMAP_SOURCE_DIR);
    std::ifstream in(source / "tests" / "workflow" / "data" / "calibrate" / "drum_friction.yaml");
    std::string text((std::istreambuf_iterator<char>(in)), {});
    text = std::regex_replace(text, std::regex("angle: [^,}]*"), "angle: " + angle);
    text =
        std::regex_replace(text, std::regex("scene: \\.\\./\\.\\./\\.\\./\\.\\./"), "scene: " + source.string() + "/");
    const fs::path file = dir_ / "drum_friction.yaml";
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

TEST_F(CalibrateRoundTrip, DrumAngleGivesBackTheFrictionThatMadeIt) {
  const fs::path out = dir_ / "out";
  const auto at = calibrate({with_angle("30 deg").string(), "--out", out.string(), "--at", "friction=0.4"});
  ASSERT_EQ(at.exit_code, 0) << at.describe();
  const double angle = read_json(out / "at.json")["tests"][0]["angle_deg"];
  std::printf("drum angle at friction 0.4 (not a design point): %.2f deg\n", angle);

  const auto run = calibrate({with_angle(std::to_string(angle) + " deg").string(), "--out", out.string()});
  ASSERT_EQ(run.exit_code, 0) << run.describe();
  const auto result = read_json(out / "calibration.json");
  const auto &mu = result["parameters"]["friction"];
  std::printf("friction %.3f (68 %% set %.3f to %.3f); surrogate leave-one-out %.2f deg\n", mu["best"].get<double>(),
              mu["lower"].get<double>(), mu["upper"].get<double>(),
              result["tests"][0]["surrogate_loo_rmse_deg"].get<double>());
  EXPECT_EQ(result["runs"], 3);
  EXPECT_LE(mu["lower"].get<double>(), 0.4);
  EXPECT_GE(mu["upper"].get<double>(), 0.4);
  // ... and the drum does identify it: a set inside the box, well narrower than it (0.29-0.52 measured).
  EXPECT_TRUE(mu["bounded"].get<bool>());
  EXPECT_LT(mu["upper"].get<double>() - mu["lower"].get<double>(), 0.4);
}

}  // namespace
