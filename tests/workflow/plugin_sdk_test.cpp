// The out-of-tree plugins (a contact law and a spreader): `cmake --install` of this build into a
// fresh prefix, then the samples in tests/plugin_sdk/ configured with find_package(spreadmap) against that prefix only,
// built, and loaded by the installed binary through SPREADMAP_PLUGIN_PATH, which must list its schema. The installed
// binary must also find the installed in-tree plugins without any variable. The plugin compiles with the project's
// warnings (-Wall -Wextra, from the installed SpreadmapWarnings.cmake) and prints none.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "workflow/installed_package.hpp"
#include "workflow/process.hpp"

namespace fs = std::filesystem;
namespace t = spreadmap::test;

namespace {

bool contains(const std::string &text, const std::string &part) { return text.find(part) != std::string::npos; }

}  // namespace

TEST(OutOfTreePlugin, BuildsAgainstTheInstalledSdkAndLoads) {
  const auto package = t::install_package("spreadmap_sdk");
  ASSERT_EQ(package.install.exit_code, 0) << package.install.describe();
  const fs::path &work = package.folder, &prefix = package.prefix, build = work / "build";
  t::expect_installed(prefix,
                      {"bin/spreadmap", "include/spreadmap/abi.h", "include/spreadmap/contact.hpp",
                       "lib/cmake/spreadmap/spreadmapConfig.cmake", "lib/cmake/spreadmap/spreadmapConfigVersion.cmake",
                       "lib/cmake/spreadmap/spreadmapTargets.cmake", "lib/cmake/spreadmap/SpreadmapPlugin.cmake",
                       "lib/cmake/spreadmap/SpreadmapWarnings.cmake", "lib/spreadmap/plugins/contact/hooke_slider.so",
                       "lib/spreadmap/plugins/spreader/roller.so"});

  const auto configure = t::configure_against(prefix, SPREADMAP_SOURCE_DIR "/tests/plugin_sdk", build);
  ASSERT_EQ(configure.exit_code, 0) << configure.describe();
  const auto compile = t::cmake({"--build", build.string(), "-j", "2", "--verbose"});
  ASSERT_EQ(compile.exit_code, 0) << compile.describe();
  EXPECT_TRUE(contains(compile.out, " -Wall ") && contains(compile.out, " -Wextra ")) << compile.out;
  EXPECT_FALSE(contains(compile.out + compile.err, "warning:")) << compile.out << compile.err;
  const fs::path plugins = build / "lib" / "spreadmap" / "plugins";
  const fs::path library = plugins / "contact" / "soft_spring.so";
  ASSERT_TRUE(fs::exists(library));

  const fs::path installed = prefix / "bin" / "spreadmap";
  const std::map<std::string, std::string> env = {{"SPREADMAP_PLUGIN_PATH", plugins.string()}};
  const auto schema = t::run({{"plugins", "soft_spring"}, installed, env, {}});
  ASSERT_EQ(schema.exit_code, 0) << schema.describe();
  EXPECT_TRUE(contains(schema.out, "contact/soft_spring 0.1.0")) << schema.out;
  for (const char *key : {"stiffness", "damping_ratio", "N/m"}) EXPECT_TRUE(contains(schema.out, key)) << schema.out;
  EXPECT_TRUE(contains(schema.out, "file: " + library.string())) << schema.out;

  const auto json = t::run({{"plugins", "--kind", "contact", "--format", "json"}, installed, env, {}});
  ASSERT_EQ(json.exit_code, 0) << json.describe();
  bool found = false;
  for (const auto &p : nlohmann::json::parse(json.out))
    if (p.at("name") == "soft_spring") {
      found = true;
      ASSERT_EQ(p.at("params").size(), 2u);
      EXPECT_EQ(p.at("params")[0].at("name"), "stiffness");
      EXPECT_EQ(p.at("params")[0].at("unit"), "N/m");
      EXPECT_EQ(p.at("params")[0].at("default").get<double>(), 500.0);
    } else {
      // the in-tree laws come from the prefix, found beside the installed binary
      EXPECT_EQ(p.at("file").get<std::string>().rfind((prefix / "lib/spreadmap/plugins/contact").string(), 0), 0u)
          << p.at("file");
    }
  EXPECT_TRUE(found) << json.out;

  // the sample is a usable contact law: a workflow can select it and validate
  const fs::path wf = work / "soft.yaml";
  {
    std::ofstream(wf) << "version: 1\nname: soft\nscene:\n  preset: quick\n"
                         "  contact: {use: soft_spring, stiffness: 300 N/m}\n"
                         "stages:\n  - simulate: {}\n";
  }
  const auto validate = t::run({{"validate", wf.string()}, installed, env, {}});
  EXPECT_EQ(validate.exit_code, 0) << validate.describe();

  // the out-of-tree spreader: listed, and a scene runs with it, the host knowing it only by what it
  // says of itself. It travels 4 mm from x = 6 mm and stops there; nothing is lost on the way.
  ASSERT_TRUE(fs::exists(plugins / "spreader" / "scraper.so"));
  const auto scraper = t::run({{"plugins", "scraper"}, installed, env, {}});
  ASSERT_EQ(scraper.exit_code, 0) << scraper.describe();
  EXPECT_TRUE(contains(scraper.out, "spreader/scraper 0.1.0")) << scraper.out;
  const fs::path scraped = work / "scraped.yaml";
  {
    std::ofstream(scraped) << "version: 1\nname: scraped\nscene:\n  preset: quick\n  powder: {count: 300}\n"
                              "  spreader: {use: scraper, thickness: 1 mm, height: 8 mm, gap: 0.4 mm, travel: 4 mm}\n"
                              "stages:\n  - simulate: {render: false}\n";
  }
  const auto run = t::run({{"run", scraped.string(), "--out", (work / "out").string()}, installed, env, {}});
  ASSERT_EQ(run.exit_code, 0) << run.describe();
  const auto record = nlohmann::json::parse(std::ifstream(work / "out" / "cases" / "c000" / "case.json"));
  EXPECT_NEAR(record["spreader_end"]["reference"][0].get<double>(), 10e-3, 1e-12) << record.dump();
  EXPECT_NEAR(record["spreader"]["gap"].get<double>(), 0.4e-3, 1e-15);
  EXPECT_EQ(record["spreader"]["outline_x"].size(), 4u);
  EXPECT_EQ(record["particles_end"].get<int>() + record["removed"].get<int>(), record["particles_start"].get<int>());
  fs::remove_all(work);
}
