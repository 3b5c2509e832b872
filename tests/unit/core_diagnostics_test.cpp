// Diagnostics: one shape for every user-facing error, "FILE:LINE:COL: key.path: what" with a
// 1-based line and column (yaml-cpp's marks are 0-based), and an indented hint line.
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include "core/diagnostics.hpp"
#include "core/error.hpp"

namespace sm = spreadmap;

TEST(CoreDiagnostics, LocationsAreOneBased) {
  const YAML::Node root = YAML::Load("version: 1\nscene:\n  powder: {diameter: 250 um}\n");
  const auto at_root = sm::Location::of("wf.yaml", root);
  EXPECT_EQ(at_root.line, 1);
  EXPECT_EQ(at_root.column, 1);
  const auto at_value = sm::Location::of("wf.yaml", root["scene"]["powder"]["diameter"]);
  EXPECT_EQ(at_value.line, 3);
  EXPECT_EQ(at_value.column, 22);
  EXPECT_EQ(at_value.str(), "wf.yaml:3:22");
}

TEST(CoreDiagnostics, UnknownPositionPrintsTheFileOnly) {
  const sm::Location none{"wf.yaml"};
  EXPECT_EQ(none.str(), "wf.yaml");
  const YAML::Node root = YAML::Load("a: 1");
  const auto missing = sm::Location::of("wf.yaml", root["nothing"]);
  EXPECT_EQ(missing.line, 0);
  EXPECT_EQ(missing.str(), "wf.yaml");
}

TEST(CoreDiagnostics, MessageShape) {
  sm::Diagnostics diag;
  EXPECT_TRUE(diag.empty());
  EXPECT_NO_THROW(diag.throw_if_any());
  diag.error({"wf.yaml", 4, 7}, "scene.powder.diameter", "outside [1e-06, 0.1] m", "diameter: sphere diameter");
  diag.error({"wf.yaml", 2, 1}, "", "a workflow is a YAML mapping");
  ASSERT_EQ(diag.errors().size(), 2u);
  EXPECT_EQ(diag.errors()[0],
            "wf.yaml:4:7: scene.powder.diameter: outside [1e-06, 0.1] m\n  diameter: sphere diameter");
  EXPECT_EQ(diag.errors()[1], "wf.yaml:2:1: a workflow is a YAML mapping");
  try {
    diag.throw_if_any();
    FAIL() << "no error";
  } catch (const sm::InputError &e) {
    EXPECT_EQ(std::string(e.what()), diag.errors()[0] + "\n" + diag.errors()[1]);
    EXPECT_EQ(e.exit_code, 2);
    EXPECT_EQ(sm::printed(e), "error: " + diag.errors()[0] + "\nerror: " + diag.errors()[1] + "\n")
        << "each message is printed after one 'error: ', the hint on its own indented line";
  }
}

TEST(CoreDiagnostics, ThousandsOfErrorsShowTheFirstFiftyAndTheCount) {
  sm::Diagnostics diag;
  for (int i = 0; i < 10000; ++i) diag.error({"wf.yaml", i + 1, 1}, "key" + std::to_string(i), "unknown key");
  EXPECT_EQ(diag.errors().size(), 10000u) << "every error is kept: callers count them to see new ones";
  try {
    diag.throw_if_any();
    FAIL() << "no error";
  } catch (const sm::InputError &e) {
    const std::string text = e.what();
    EXPECT_NE(text.find("wf.yaml:50:1: key49: unknown key\n"), std::string::npos);
    EXPECT_EQ(text.find("key50:"), std::string::npos) << "the 51st is not shown";
    const std::string tail = "\n... and 9950 more errors (fix these and run again to see them)";
    ASSERT_GE(text.size(), tail.size());
    EXPECT_EQ(text.substr(text.size() - tail.size()), tail);
    const std::string shown = sm::printed(e);
    std::size_t prefixed = 0;
    for (std::size_t at = shown.find("error: "); at != std::string::npos; at = shown.find("error: ", at + 1)) ++prefixed;
    EXPECT_EQ(prefixed, 50u) << "one 'error: ' per message shown, none before the count of the rest";
    EXPECT_EQ(shown.substr(shown.size() - tail.size()), tail.substr(1) + "\n");
  }
}

// A message carries no prefix (it is also quoted inside warnings and other messages); printing adds
// it once, to errors of every kind.
TEST(CoreDiagnostics, PrintingAddsTheErrorPrefixOnce) {
  EXPECT_EQ(sm::printed(sm::RunFailure("cannot write a.csv: disk full\n  free some space")),
            "error: cannot write a.csv: disk full\n  free some space\n");
  EXPECT_EQ(sm::printed(std::runtime_error("bad_alloc")), "error: bad_alloc\n");
  EXPECT_EQ(sm::printed(sm::Interrupted("interrupted: finished cases are kept")), "interrupted: finished cases are kept\n")
      << "a stop the user asked for is no error";
  EXPECT_EQ(sm::printed(sm::InputError({"a.yaml:1:1: x: unknown key", "a.yaml:2:1: y: unknown key"}, "")),
            "error: a.yaml:1:1: x: unknown key\nerror: a.yaml:2:1: y: unknown key\n");
}

TEST(CoreDiagnostics, ExitCodesAreDistinct) {
  EXPECT_EQ(sm::InputError("x").exit_code, 2);
  EXPECT_EQ(sm::PluginError("x").exit_code, 3);
  EXPECT_EQ(sm::RunFailure("x").exit_code, 1);
  EXPECT_EQ(sm::Interrupted("x").exit_code, 130);
}
