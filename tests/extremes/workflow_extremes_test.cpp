// The whole path at the extremes: small workflow files run by the real binary. A step below dt_crit
// runs and writes finite, physical results; a step above it is refused with exit code 2 and a
// message naming both steps and the fix; a scene whose contacts are too soft for its speeds stops
// with exit code 1 and a clear message; an empty heap is refused before any work; a single sphere
// runs. Whatever happens, no file under the run directory holds a NaN or an infinity.
#include <gtest/gtest.h>

#include <engine/stability.hpp>
#include <engine/vtp_io.hpp>
#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <spreadmap/contact_parts.hpp>

#include <cmath>
#include <fstream>
#include <functional>
#include <regex>
#include <sstream>

#include "extremes/checks.hpp"
#include "workflow/process.hpp"

namespace fs = std::filesystem;
namespace test = spreadmap::test;
using namespace spreadmap::extremes;

namespace {

// The quick preset's contacts (v_max 0.5 m/s, overlap_max 5 um, restitution 0.8 everywhere): the
// critical step every scene below shares.
double quick_dt_crit() {
  const double f = spreadmap::engine::packing_frequency_factor;
  return spreadmap::engine::stable_omega_dt(f * spreadmap::damping_ratio_from_restitution(0.8)) / (f * 0.5 / 5e-6);
}

// A tiny spreading scene on the quick preset: `count` spheres inserted below 1 mm and settled for
// 20 ms, the roller over 8 mm at U = 500 mm/s. `scene_extra` adds keys (YAML flow-map items).
struct TinyWorkflow {
  int count = 20;
  double U_mm_s = 500, omega = -100, gap_um = 500;
  std::string contact_extra, time = "safety: 0.4";
};

std::string workflow_text(const TinyWorkflow &s) {
  return fmt::format(R"(version: 1
name: extremes
scene:
  preset: quick
  powder: {{count: {}, heap_top: 1 mm, settle_time: 0.02 s}}
  spreader: {{use: roller, travel: 8 mm, U: {} mm/s, omega: {} rad/s, gap: {} um}}
  contact: {{use: hooke_slider{}}}
  time: {{{}, relax: 0.005 s}}
stages:
  - simulate: {{render: false}}
)",
                     s.count, s.U_mm_s, s.omega, s.gap_um, s.contact_extra, s.time);
}

class BinaryRun {
 public:
  explicit BinaryRun(const TinyWorkflow &scene) {
    const auto *info = ::testing::UnitTest::GetInstance()->current_test_info();
    std::string name = std::string(info->test_suite_name()) + "_" + info->name();
    for (char &c : name)
      if (c == '/') c = '_';
    dir_ = fs::temp_directory_path() / ("spreadmap_extremes_" + name);
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    std::ofstream(dir_ / "wf.yaml") << workflow_text(scene);
    outcome_ = test::run({{"run", (dir_ / "wf.yaml").string(), "--out", out().string()}, {}, {}, {}});
  }
  ~BinaryRun() {
    if (!::testing::Test::HasFailure()) fs::remove_all(dir_);
  }
  fs::path out() const { return dir_ / "out"; }
  fs::path case_dir() const { return out() / "cases" / "c000"; }
  const test::Outcome &outcome() const { return outcome_; }

 private:
  fs::path dir_;
  test::Outcome outcome_;
};

std::string slurp(const fs::path &p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// Every file under `dir`: no "nan"/"inf" token in any text, every .vtp readable with finite
// columns, every number in every .json finite. nlohmann writes NaN as null, so case.json (numbers
// and words only, no optional entries) must hold no null either.
void expect_no_non_finite_files(const fs::path &dir) {
  if (!fs::exists(dir)) return;
  const std::regex token(R"((^|[^A-Za-z_])(nan|inf|infinity)([^A-Za-z_]|$))", std::regex::icase);
  for (const auto &entry : fs::recursive_directory_iterator(dir)) {
    if (!entry.is_regular_file()) continue;
    const fs::path p = entry.path();
    const std::string text = slurp(p);
    EXPECT_FALSE(std::regex_search(text, token)) << p << " holds a NaN or infinity";
    if (p.extension() == ".vtp") {
      EXPECT_EQ(first_non_finite(spreadmap::engine::read_vtp(p).particles), "") << p;
    }
    if (p.extension() == ".json") {
      std::function<void(const nlohmann::json &, const std::string &)> walk = [&](const nlohmann::json &j,
                                                                                  const std::string &at) {
        if (j.is_null() && p.filename() == "case.json") ADD_FAILURE() << p << ": null at " << at << " (a NaN?)";
        if (j.is_number_float()) {
          EXPECT_TRUE(std::isfinite(j.get<double>())) << p << " at " << at;
        }
        if (j.is_structured())
          for (auto it = j.begin(); it != j.end(); ++it) walk(*it, at + "/" + (j.is_object() ? it.key() : "[]"));
      };
      walk(nlohmann::json::parse(text), "");
    }
  }
}

// A finished case's physical truths: finite, nothing lost, nothing inside the substrate or the
// roller (at its final pose) beyond the overlap limit.
void expect_physical_case(const fs::path &case_dir, int count) {
  const auto j = nlohmann::json::parse(slurp(case_dir / "case.json"));
  const auto s = spreadmap::engine::read_vtp(case_dir / "state.vtp").particles;
  EXPECT_EQ(first_non_finite(s), "");
  EXPECT_EQ(int(s.size()) + j["removed"].get<int>(), count);
  EXPECT_LE(deepest_substrate_overlap(s), 0.1);
  // the roller's axis where it stopped, and its radius from the outline it recorded (a disc about the axis)
  const double ax = j["spreader_end"]["reference"][0], az = j["spreader_end"]["reference"][2];
  const double R = std::hypot(j["spreader"]["outline_x"][0].get<double>(), j["spreader"]["outline_z"][0].get<double>());
  for (std::size_t i = 0; i < s.size(); ++i) {
    const double dist = std::hypot(s.x[i] - ax, s.z[i] - az);
    EXPECT_GE(dist, R + s.radius[i] - 0.1 * 2 * s.radius[i]) << "sphere id " << s.id[i] << " inside the roller";
  }
}

std::string factor_name(double f) { return "x" + std::to_string(int(std::lround(f * 10))) + "_tenths"; }

}  // namespace

class WorkflowStableStep : public ::testing::TestWithParam<double> {};

TEST_P(WorkflowStableStep, RunsAndWritesFinitePhysicalResults) {
  const double crit = quick_dt_crit(), dt = GetParam() * crit;
  TinyWorkflow scene;
  scene.time = fmt::format("step: {:.17g} s", dt);
  const BinaryRun run(scene);
  ASSERT_EQ(run.outcome().exit_code, 0) << run.outcome().describe();
  const auto j = nlohmann::json::parse(slurp(run.case_dir() / "case.json"));
  EXPECT_NEAR(j["dt_critical"].get<double>(), crit, 1e-12 * crit);
  EXPECT_NEAR(j["dt"].get<double>(), dt, 1e-12 * dt);
  expect_physical_case(run.case_dir(), scene.count);
  expect_no_non_finite_files(run.out());
}

INSTANTIATE_TEST_SUITE_P(BelowTheLimit, WorkflowStableStep, ::testing::Values(0.5, 0.9),
                         [](const auto &info) { return factor_name(info.param); });

class WorkflowUnstableStep : public ::testing::TestWithParam<double> {};

TEST_P(WorkflowUnstableStep, IsRefusedWithBothStepsAndTheFix) {
  const double crit = quick_dt_crit(), dt = GetParam() * crit;
  TinyWorkflow scene;
  scene.time = fmt::format("step: {:.17g} s", dt);
  const BinaryRun run(scene);
  const auto &o = run.outcome();
  ASSERT_TRUE(o.exited) << o.describe();
  EXPECT_EQ(o.exit_code, 2) << o.describe();
  EXPECT_NE(o.err.find(fmt::format("time step dt = {:.6g} s", dt)), std::string::npos) << o.err;
  EXPECT_NE(o.err.find(fmt::format("dt_crit = {:.6g} s", crit)), std::string::npos) << o.err;
  EXPECT_NE(o.err.find(fmt::format("use dt <= {:.6g} s", crit)), std::string::npos) << o.err;
  EXPECT_EQ(test::crash_marker(o.err), "") << o.err;
  EXPECT_FALSE(fs::exists(run.case_dir() / "state.vtp"));
  expect_no_non_finite_files(run.out());
}

INSTANTIATE_TEST_SUITE_P(AboveTheLimit, WorkflowUnstableStep, ::testing::Values(1.1, 2.0, 5.0),
                         [](const auto &info) { return factor_name(info.param); });

TEST(WorkflowExtremes, TooSoftContactsStopWithAClearError) {
  // V_max = 20 mm/s against a roller surface moving at 1 m/s with a gap of 0.6 d: overlaps far
  // beyond 10 % of the diameter. The case stops with exit code 1, says what to change, and leaves
  // no NaN behind.
  TinyWorkflow scene;
  scene.contact_extra = ", v_max: 20 mm/s";
  scene.gap_um = 150;
  const BinaryRun run(scene);
  const auto &o = run.outcome();
  ASSERT_TRUE(o.exited) << o.describe();
  EXPECT_EQ(o.exit_code, 1) << o.describe();
  EXPECT_NE(o.err.find("overlap too large"), std::string::npos) << o.err;
  EXPECT_NE(o.err.find("stiffen the contact law"), std::string::npos) << o.err;
  EXPECT_EQ(test::crash_marker(o.err), "") << o.err;
  EXPECT_FALSE(fs::exists(run.case_dir() / "state.vtp"));
  expect_no_non_finite_files(run.out());
}

TEST(WorkflowExtremes, EmptyHeapIsRefusedBeforeAnyWork) {
  TinyWorkflow scene;
  scene.count = 0;
  const BinaryRun run(scene);
  const auto &o = run.outcome();
  ASSERT_TRUE(o.exited) << o.describe();
  EXPECT_EQ(o.exit_code, 2) << o.describe();
  EXPECT_NE(o.err.find("scene.powder.count"), std::string::npos) << o.err;
  EXPECT_NE(o.err.find("no powder"), std::string::npos) << o.err;
  EXPECT_FALSE(fs::exists(run.case_dir())) << "a case was started for an empty heap";
  expect_no_non_finite_files(run.out());
}

TEST(WorkflowExtremes, SingleSphereUnderAFastNarrowRollerRuns) {
  // One sphere, U = 500 mm/s, omega = -100 rad/s, gap 0.6 d: pushed ahead, finite, nothing inside.
  TinyWorkflow scene;
  scene.count = 1;
  scene.gap_um = 150;
  const BinaryRun run(scene);
  ASSERT_EQ(run.outcome().exit_code, 0) << run.outcome().describe();
  expect_physical_case(run.case_dir(), 1);
  expect_no_non_finite_files(run.out());
}
