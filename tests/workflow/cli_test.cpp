// The command line as users meet it first: --version, the plugin reference manual (table and JSON,
// the four kinds), every shipped workflow validates, and plugin faults reached through
// `spreadmap plugins NAME` are plugin errors (exit 3) naming the library, never crashes.
#include <gtest/gtest.h>
#include <spreadmap/abi.h>

#include <nlohmann/json.hpp>
#include <regex>
#include <set>
#include <sstream>

#include "workflow/process.hpp"

namespace fs = std::filesystem;
namespace t = spreadmap::test;

namespace {

const std::set<std::string> kinds = {"contact", "spreader", "metrics", "surrogate"};

bool contains(const std::string &text, const std::string &part) { return text.find(part) != std::string::npos; }

t::Outcome cli(std::vector<std::string> args, std::map<std::string, std::string> env = {}) {
  return t::run({std::move(args), {}, std::move(env), {}});
}

std::string fixture(const std::string &fault) { return (fs::path(SPREADMAP_FIXTURE_DIR) / fault).string(); }

// A clean plugin error: exit 3, an error line naming `file`, nothing that looks like a crash.
void expect_plugin_error(const t::Outcome &r, const std::string &file, const std::string &what) {
  ASSERT_TRUE(r.exited) << r.describe();
  EXPECT_EQ(r.exit_code, 3) << r.describe();
  EXPECT_EQ(t::crash_marker(r.err), "") << r.describe();
  EXPECT_TRUE(contains(r.err, "error: " + file)) << r.describe();
  EXPECT_TRUE(contains(r.err, what)) << r.describe();
}

}  // namespace

TEST(Cli, VersionNamesTheProgramAndThePluginAbi) {
  const auto r = cli({"--version"});
  ASSERT_EQ(r.exit_code, 0) << r.describe();
  EXPECT_TRUE(std::regex_match(r.out, std::regex("spreadmap [0-9]+\\.[0-9]+\\.[0-9]+ \\(plugin ABI " +
                                                 std::to_string(SPREADMAP_PLUGIN_ABI_MAJOR) + "\\." +
                                                 std::to_string(SPREADMAP_PLUGIN_ABI_MINOR) + "\\)\n")))
      << r.out;
}

TEST(Cli, PluginsListsEveryKind) {
  const auto r = cli({"plugins"});
  ASSERT_EQ(r.exit_code, 0) << r.describe();
  std::set<std::string> seen;
  std::istringstream lines(r.out);
  for (std::string line; std::getline(lines, line);) {
    std::istringstream words(line);
    std::string kind, name;
    words >> kind >> name;
    EXPECT_EQ(kinds.count(kind), 1u) << "not a kind: " << line;
    seen.insert(kind);
  }
  EXPECT_EQ(seen, kinds);
  for (const char *name : {"hooke_slider", "roller", "blade", "layer", "bpnn", "gp"})
    EXPECT_TRUE(contains(r.out, name)) << name;
}

TEST(Cli, PluginsAsJsonCarryTheWholeSchema) {
  const auto r = cli({"plugins", "--format", "json"});
  ASSERT_EQ(r.exit_code, 0) << r.describe();
  const auto all = nlohmann::json::parse(r.out);
  ASSERT_TRUE(all.is_array());
  std::set<std::string> seen;
  for (const auto &p : all) {
    seen.insert(p.at("kind").get<std::string>());
    EXPECT_TRUE(fs::exists(p.at("file").get<std::string>())) << p.dump();
    EXPECT_FALSE(p.at("version").get<std::string>().empty());
    for (const auto &param : p.at("params")) {
      for (const char *field : {"name", "type", "unit", "doc", "required"})
        EXPECT_TRUE(param.contains(field)) << param.dump();
      EXPECT_FALSE(param.at("doc").get<std::string>().empty())
          << p.at("name") << "." << param.at("name") << " has no doc";
      if (!param.at("required").get<bool>() && param.at("type") != "table") {
        EXPECT_TRUE(param.contains("default")) << param.dump();
      }
    }
  }
  EXPECT_EQ(seen, kinds);
}

TEST(Cli, PluginsNamePrintsItsSchema) {
  const auto r = cli({"plugins", "roller"});
  ASSERT_EQ(r.exit_code, 0) << r.describe();
  EXPECT_TRUE(contains(r.out, "spreader/roller")) << r.out;
  for (const char *key : {"diameter", "gap", "omega", "travel"}) EXPECT_TRUE(contains(r.out, key)) << key;
  EXPECT_TRUE(contains(r.out, "file: ")) << r.out;
}

// What the stages choose a plugin by (plugin_needs.hpp) is printed beside its parameters: a metrics
// plugin's declared metrics with their units, a surrogate's predictive standard deviation.
TEST(Cli, PluginsNamePrintsWhatTheStagesChooseItBy) {
  const auto layer = cli({"plugins", "layer"});
  ASSERT_EQ(layer.exit_code, 0) << layer.describe();
  EXPECT_TRUE(contains(layer.out, "gives (every evaluation):")) << layer.out;
  std::istringstream lines(layer.out);
  std::set<std::string> declared;
  for (std::string line; std::getline(lines, line);) {
    std::istringstream words(line);
    std::string name, unit;
    if (line.rfind("    ", 0) == 0 && words >> name >> unit) declared.insert(name + " " + unit);
  }
  EXPECT_TRUE(declared.count("vs m^2/s") && declared.count("rq m")) << layer.out;
  const auto gp = cli({"plugins", "gp"});
  ASSERT_EQ(gp.exit_code, 0) << gp.describe();
  EXPECT_TRUE(contains(gp.out, "predictive standard deviation: yes")) << gp.out;
  const auto all = nlohmann::json::parse(cli({"plugins", "--format", "json"}).out);
  for (const auto &p : all) {
    if (p.at("kind") == "metrics") {
      EXPECT_FALSE(p.at("gives").empty()) << p.dump();
    }
    if (p.at("kind") == "surrogate") {
      EXPECT_TRUE(p.contains("predictive_std")) << p.dump();
    }
  }
}

TEST(Cli, PluginsOfOneKind) {
  const auto r = cli({"plugins", "--kind", "contact"});
  ASSERT_EQ(r.exit_code, 0) << r.describe();
  std::istringstream lines(r.out);
  for (std::string line; std::getline(lines, line);) EXPECT_EQ(line.rfind("contact ", 0), 0u) << line;
  const auto bad = cli({"plugins", "--kind", "contacts"});
  EXPECT_EQ(bad.exit_code, 2) << bad.describe();
  EXPECT_TRUE(contains(bad.err, "not a plugin kind")) << bad.err;
}

TEST(Cli, UnknownPluginNameSuggestsTheClosest) {
  const auto r = cli({"plugins", "rollr"});
  ASSERT_TRUE(r.exited);
  EXPECT_EQ(r.exit_code, 2) << r.describe();
  EXPECT_TRUE(contains(r.err, "did you mean 'roller'?")) << r.err;
}

TEST(Cli, UnknownCommandSuggestsTheClosest) {
  const auto r = cli({"valdate", "x.yaml"});
  EXPECT_EQ(r.exit_code, 2) << r.describe();
  EXPECT_TRUE(contains(r.err, "did you mean 'validate'?")) << r.err;
}

TEST(Cli, EverySubCommandHasHelp) {
  for (const char *cmd : {"run", "validate", "plugins"}) {
    const auto r = cli({cmd, "--help"});
    EXPECT_EQ(r.exit_code, 0) << cmd << ": " << r.describe();
    EXPECT_TRUE(contains(r.out, std::string("usage: spreadmap ") + cmd)) << r.out;
  }
}

TEST(Cli, MissingOrUnreadableWorkflowIsAnInputError) {
  const auto none = cli({"validate"});
  EXPECT_EQ(none.exit_code, 2) << none.describe();
  const auto missing = cli({"validate", "/nonexistent/wf.yaml"});
  EXPECT_EQ(missing.exit_code, 2) << missing.describe();
  EXPECT_TRUE(contains(missing.err, "/nonexistent/wf.yaml")) << missing.err;
}

TEST(Cli, EveryShippedWorkflowValidates) {
  const fs::path dir = fs::path(SPREADMAP_SOURCE_DIR) / "workflows";
  std::size_t n = 0;
  for (const auto &e : fs::directory_iterator(dir)) {
    if (e.path().extension() != ".yaml") continue;
    ++n;
    const auto r = cli({"validate", e.path().string()});
    EXPECT_EQ(r.exit_code, 0) << e.path() << "\n" << r.describe();
    EXPECT_TRUE(contains(r.out, e.path().string() + ": ok")) << r.out;
  }
  EXPECT_GE(n, 1u) << "no workflow in " << dir;
}

// The plugin faults of the registry tests, reached the way a user would: through the plugin path.
TEST(CliPluginFaults, AbiMismatchNamesTheFileAndBothVersions) {
  const auto r = cli({"plugins", "abi_mismatch"}, {{"SPREADMAP_PLUGIN_PATH", fixture("abi_mismatch")}});
  expect_plugin_error(r, fixture("abi_mismatch") + "/contact/abi_mismatch.so",
                      "uses plugin ABI 99, this host loads ABI " + std::to_string(SPREADMAP_PLUGIN_ABI_MAJOR) +
                          ".0 to " + std::to_string(SPREADMAP_PLUGIN_ABI_MAJOR) + "." +
                          std::to_string(SPREADMAP_PLUGIN_ABI_MINOR));
}

TEST(CliPluginFaults, LibraryWithoutEntryPoint) {
  const auto r = cli({"plugins", "no_entry"}, {{"SPREADMAP_PLUGIN_PATH", fixture("no_entry")}});
  expect_plugin_error(r, fixture("no_entry") + "/contact/no_entry.so", "no entry point 'spreadmap_plugin_v1'");
}

TEST(CliPluginFaults, EntryPointWithoutDescriptor) {
  const auto r = cli({"plugins", "null_descriptor"}, {{"SPREADMAP_PLUGIN_PATH", fixture("null_descriptor")}});
  expect_plugin_error(r, fixture("null_descriptor") + "/contact/null_descriptor.so", "returned no descriptor");
}

TEST(CliPluginFaults, NameThatDiffersFromTheFile) {
  const auto r = cli({"plugins", "name_mismatch"}, {{"SPREADMAP_PLUGIN_PATH", fixture("name_mismatch")}});
  expect_plugin_error(r, fixture("name_mismatch") + "/contact/name_mismatch.so", "registers the name 'other_name'");
}

TEST(CliPluginFaults, StaleCopyFirstInThePathWins) {
  const auto r = cli({"plugins", "hooke_slider"}, {{"SPREADMAP_PLUGIN_PATH", fixture("stale_hooke_slider")}});
  expect_plugin_error(r, fixture("stale_hooke_slider") + "/contact/hooke_slider.so", "uses plugin ABI 99");
}

TEST(CliPluginFaults, FirstCopyInThePathWinsAndTheShadowIsLogged) {
  const auto r =
      cli({"plugins", "fixture_law"}, {{"SPREADMAP_PLUGIN_PATH", fixture("shadow") + ":" + fixture("good")}});
  ASSERT_EQ(r.exit_code, 0) << r.describe();
  EXPECT_TRUE(contains(r.out, "contact/fixture_law 2.0.0")) << r.out;
  EXPECT_TRUE(contains(r.out, "file: " + fixture("shadow") + "/contact/fixture_law.so")) << r.out;
  EXPECT_TRUE(contains(r.err, "shadows " + fixture("good") + "/contact/fixture_law.so")) << r.err;
}
