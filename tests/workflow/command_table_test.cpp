// The command and stage tables (host/cli/command_table.hpp, host/workflow/stage_table.hpp) are the
// only lists of names: the usage, each command's --help, the did-you-mean of a mistyped command,
// `spreadmap stages` (table and JSON), the stages a workflow accepts and `run --only`'s help all
// agree with them, read here from the tables themselves.
#include <gtest/gtest.h>

#include <unistd.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <yaml-cpp/yaml.h>

#include "cli/command_table.hpp"
#include "core/diagnostics.hpp"
#include "core/suggest.hpp"
#include "workflow/process.hpp"
#include "workflow/stage_table.hpp"

namespace fs = std::filesystem;
namespace t = spreadmap::test;
namespace cli = spreadmap::cli;

namespace {

bool contains(const std::string &text, const std::string &part) { return text.find(part) != std::string::npos; }

std::size_t count(const std::string &text, const std::string &part) {
  std::size_t n = 0;
  for (std::size_t at = text.find(part); at != std::string::npos; at = text.find(part, at + 1)) ++n;
  return n;
}

t::Outcome spreadmap_says(std::vector<std::string> args) { return t::run({std::move(args), {}, {}, {}}); }

// The name with its last two letters swapped ("stages" -> "stagse"): a typo one step away.
std::string typo(std::string name) {
  std::swap(name[name.size() - 1], name[name.size() - 2]);
  return name;
}

}  // namespace

TEST(CommandTable, TheUsageListsEveryCommandOnceWithItsArguments) {
  const t::Outcome help = spreadmap_says({"--help"});
  ASSERT_EQ(help.exit_code, 0) << help.describe();
  for (const auto &c : cli::command_table()) {
    EXPECT_TRUE(contains(help.out, "\n  " + c.name + " " + c.args + " ")) << c.name << "\n" << help.out;
    EXPECT_EQ(count(help.out, "\n  " + c.name + " "), 1u) << c.name;
  }
  EXPECT_EQ(cli::usage(), help.out);
}

TEST(CommandTable, EveryCommandAndAliasAnswersHelpUnderItsName) {
  for (const auto &c : cli::command_table())
    for (const std::string &name : {c.name, c.alias}) {
      if (name.empty()) continue;
      const t::Outcome r = spreadmap_says({name, "--help"});
      EXPECT_EQ(r.exit_code, 0) << name << ": " << r.describe();
      EXPECT_TRUE(contains(r.out, "usage: spreadmap " + c.name)) << name << ":\n" << r.out;
    }
}

TEST(CommandTable, AMistypedCommandIsAnsweredWithTheCommandMeant) {
  for (const auto &c : cli::command_table()) {
    const std::string wrong = typo(c.name);
    if (cli::find_command(wrong)) continue;
    const t::Outcome r = spreadmap_says({wrong});
    EXPECT_EQ(r.exit_code, 2) << r.describe();
    EXPECT_TRUE(contains(r.err, "unknown command '" + wrong + "'; did you mean '" + c.name + "'?")) << r.err;
  }
}

TEST(CommandTable, EveryStageWithACommandIsACommandAndEveryStageIsListed) {
  const t::Outcome list = spreadmap_says({"stages"});
  ASSERT_EQ(list.exit_code, 0) << list.describe();
  std::size_t lines = 0;
  for (const auto &s : spreadmap::stage_table()) {
    EXPECT_TRUE(contains(list.out, std::string(s.name) + " ")) << s.name;
    ++lines;
    const auto *c = cli::find_command(s.name);
    EXPECT_EQ(c != nullptr, s.command != nullptr) << s.name;
    if (c) {
      EXPECT_EQ(c->stage, &s) << s.name;
    }
  }
  EXPECT_EQ(count(list.out, "\n"), lines);
}

TEST(CommandTable, StagesNamePrintsEverySettingOfTheStagesSchema) {
  for (const auto &s : spreadmap::stage_table()) {
    const t::Outcome r = spreadmap_says({"stages", s.name});
    ASSERT_EQ(r.exit_code, 0) << r.describe();
    EXPECT_TRUE(contains(r.out, std::string("stage ") + s.name + " — " + s.summary)) << r.out;
    for (std::size_t i = 0; i < s.settings.n; ++i)
      EXPECT_TRUE(contains(r.out, std::string("\n  ") + s.settings.params[i].name + " ")) << s.name << ": " << r.out;
    const t::Outcome json = spreadmap_says({"stages", s.name, "--format", "json"});
    ASSERT_EQ(json.exit_code, 0) << json.describe();
    const auto doc = nlohmann::json::parse(json.out);
    ASSERT_EQ(doc.size(), 1u);
    EXPECT_EQ(doc[0]["name"], s.name);
    EXPECT_EQ(doc[0]["settings"].size(), s.settings.n);
  }
  const t::Outcome wrong = spreadmap_says({"stages", "mapp"});
  EXPECT_EQ(wrong.exit_code, 2);
  EXPECT_TRUE(contains(wrong.err, "no stage named 'mapp'; did you mean 'map'?")) << wrong.err;
}

TEST(CommandTable, AWorkflowAcceptsExactlyTheStagesOfTheTable) {
  const fs::path dir = fs::temp_directory_path() / ("spreadmap_command_table_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const fs::path file = dir / "w.yaml";
  std::ofstream(file) << "version: 1\nname: w\nstages:\n  - mapp: {}\n";
  const t::Outcome r = spreadmap_says({"validate", file.string()});
  EXPECT_EQ(r.exit_code, 2) << r.describe();
  EXPECT_TRUE(contains(r.err, file.string() + ":4:5: stages[0]: unknown stage 'mapp'")) << r.err;
  EXPECT_TRUE(contains(r.err, "did you mean 'map'? stages: " + spreadmap::join(spreadmap::stage_names()))) << r.err;
  std::string run_help = spreadmap_says({"run", "--help"}).out, names = spreadmap::join(spreadmap::stage_names());
  for (std::string *s : {&run_help, &names}) std::erase_if(*s, [](char c) { return std::isspace(c); });  // wrapped
  EXPECT_TRUE(contains(run_help, "(of" + names + ")")) << run_help;
  fs::remove_all(dir);
}

// A stage's defaults are written once, in its schema: a setting not given, or refused, reads as the
// schema's default (the refusal is still an error, named once).
TEST(CommandTable, ARefusedStageSettingReadsAsTheSchemasDefaultAndIsNamedOnce) {
  const spreadmap::StageInfo *train = spreadmap::find_stage("train");
  ASSERT_NE(train, nullptr);
  const double folds_default = train->settings.find("folds")->def;
  spreadmap::Diagnostics diag;
  const YAML::Node config = YAML::Load("{folds: -3, seed: 7}");
  const nlohmann::json settings = spreadmap::check_stage_settings(*train, config, "w.yaml", diag);
  EXPECT_EQ(diag.errors().size(), 1u);
  EXPECT_EQ(settings.at("folds").get<double>(), folds_default);
  EXPECT_EQ(settings.at("seed").get<long>(), 7);
  EXPECT_EQ(settings.at("split").get<std::string>(), "auto");  // not given: the default
}
