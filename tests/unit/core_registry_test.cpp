// The plugin registry against faulty libraries built by tests/unit/core.cmake: each fault is a
// PluginError (exit code 3) whose message names the file and what is wrong, never a crash; unknown
// names list what exists and suggest the closest; the first root wins and a shadowed copy is logged.
#include <gtest/gtest.h>
#include <spdlog/sinks/ostream_sink.h>
#include <spdlog/spdlog.h>
#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <sstream>

#include "core/error.hpp"
#include "core/plugin_abi.hpp"
#include "core/registry.hpp"

namespace sm = spreadmap;
namespace fs = std::filesystem;

namespace {

const fs::path fixtures = SPREADMAP_FIXTURE_DIR;

fs::path library(const std::string &fault, const std::string &stem) {
  return fixtures / fault / "contact" / (stem + ".so");
}

bool contains(const std::string &text, const std::string &part) { return text.find(part) != std::string::npos; }

// The PluginError text of get(kind, name) over `roots`; fails the test when nothing is thrown.
std::string get_error(const std::vector<fs::path> &roots, const std::string &kind, const std::string &name) {
  sm::PluginRegistry reg(roots);
  try {
    reg.get(kind, name);
  } catch (const sm::PluginError &e) {
    EXPECT_EQ(e.exit_code, sm::exit_plugin);
    return e.what();
  }
  ADD_FAILURE() << kind << "/" << name << " loaded without an error";
  return "";
}

// Captures what the registry logs while alive; restores the previous logger.
class LogCapture {
 public:
  LogCapture() : previous_(spdlog::default_logger()) {
    auto sink = std::make_shared<spdlog::sinks::ostream_sink_mt>(text_);
    auto logger = std::make_shared<spdlog::logger>("capture", sink);
    logger->set_pattern("%v");
    spdlog::set_default_logger(logger);
  }
  ~LogCapture() { spdlog::set_default_logger(previous_); }
  std::vector<std::string> lines() const {
    std::vector<std::string> out;
    std::istringstream in(text_.str());
    for (std::string l; std::getline(in, l);) out.push_back(l);
    return out;
  }

 private:
  std::ostringstream text_;
  std::shared_ptr<spdlog::logger> previous_;
};

// Sets an environment variable for one scope.
class ScopedEnv {
 public:
  ScopedEnv(const char *name, const char *value) : name_(name) {
    if (const char *old = std::getenv(name)) old_ = old, had_ = true;
    ::setenv(name, value, 1);
  }
  ~ScopedEnv() {
    if (had_) ::setenv(name_.c_str(), old_.c_str(), 1);
    else ::unsetenv(name_.c_str());
  }

 private:
  std::string name_, old_;
  bool had_ = false;
};

}  // namespace

TEST(CoreRegistry, AGoodPluginLoadsByKindAndName) {
  sm::PluginRegistry reg({fixtures / "good"});
  EXPECT_EQ(reg.names("contact"), (std::vector<std::string>{"fixture_law"}));
  const auto &p = reg.get("contact", "fixture_law");
  EXPECT_EQ(p.id(), "contact/fixture_law");
  EXPECT_EQ(std::string(p.descriptor->version), "1.0.0");
  EXPECT_EQ(p.descriptor->n_params, 4u);
  EXPECT_EQ(fs::canonical(p.file), fs::canonical(library("good", "fixture_law")));
  EXPECT_EQ(&reg.get("contact", "fixture_law"), &p);  // loaded once
}

// A plugin of a newer minor version may expect calls this host does not make: refused, naming both.
TEST(CoreRegistry, ANewerMinorAbiIsRefusedNamingBothVersionsAndTheFix) {
  const std::string e = get_error({fixtures / "newer_minor"}, "contact", "newer_minor");
  EXPECT_TRUE(contains(e, library("newer_minor", "newer_minor").string())) << e;
  EXPECT_TRUE(contains(e, "uses plugin ABI 10.99, newer than this host's " + sm::host_abi_text())) << e;
  EXPECT_TRUE(contains(e, "-DSPREADMAP_TARGET_ABI_MINOR=" + std::to_string(SPREADMAP_PLUGIN_ABI_MINOR))) << e;
}

TEST(CoreRegistry, AbiVersionsReadAsMajorDotMinorAndTheOldCountsAsTheyWere) {
  EXPECT_EQ(sm::abi_text(SPREADMAP_ABI_VERSION(10u, 1u)), "10.1");
  EXPECT_EQ(sm::abi_text(9u), "9");
  EXPECT_EQ(sm::abi_refusal(SPREADMAP_ABI_VERSION(10u, 0u)), "") << "an older minor loads";
  EXPECT_EQ(sm::abi_refusal(SPREADMAP_ABI_VERSION(10u, SPREADMAP_PLUGIN_ABI_MINOR)), "");
  EXPECT_NE(sm::abi_refusal(SPREADMAP_ABI_VERSION(11u, 0u)), "") << "another major does not";
  EXPECT_NE(sm::abi_refusal(9u), "");
}

TEST(CoreRegistry, AbiMismatchNamesTheFileAndBothVersions) {
  const std::string e = get_error({fixtures / "abi_mismatch"}, "contact", "abi_mismatch");
  EXPECT_TRUE(contains(e, library("abi_mismatch", "abi_mismatch").string())) << e;
  EXPECT_TRUE(contains(e, "uses plugin ABI 99")) << e;
  EXPECT_TRUE(contains(e, "this host loads ABI 10.0 to " + sm::host_abi_text())) << e;
  EXPECT_TRUE(contains(e, "rebuild it")) << e;
}

TEST(CoreRegistry, LibraryWithoutTheEntryPoint) {
  const std::string e = get_error({fixtures / "no_entry"}, "contact", "no_entry");
  EXPECT_TRUE(contains(e, library("no_entry", "no_entry").string())) << e;
  EXPECT_TRUE(contains(e, "is not a spreadmap plugin: it has no entry point 'spreadmap_plugin_v1'")) << e;
}

TEST(CoreRegistry, EntryPointExportedAsAVariableIsRefusedNotCalled) {
  const std::string e = get_error({fixtures / "entry_variable"}, "contact", "entry_variable");
  EXPECT_TRUE(contains(e, library("entry_variable", "entry_variable").string())) << e;
  EXPECT_TRUE(contains(e, "exports 'spreadmap_plugin_v1' as data, not as a function")) << e;
}

TEST(CoreRegistry, EntryPointReturningNothing) {
  const std::string e = get_error({fixtures / "null_descriptor"}, "contact", "null_descriptor");
  EXPECT_TRUE(contains(e, library("null_descriptor", "null_descriptor").string())) << e;
  EXPECT_TRUE(contains(e, "returned no descriptor")) << e;
}

TEST(CoreRegistry, KindThatDoesNotMatchItsFolder) {
  const std::string e = get_error({fixtures / "kind_mismatch"}, "contact", "kind_mismatch");
  EXPECT_TRUE(contains(e, library("kind_mismatch", "kind_mismatch").string())) << e;
  EXPECT_TRUE(contains(e, "is a spreader plugin, found where contact plugins are searched")) << e;
}

TEST(CoreRegistry, NameThatDoesNotMatchItsFile) {
  const std::string e = get_error({fixtures / "name_mismatch"}, "contact", "name_mismatch");
  EXPECT_TRUE(contains(e, library("name_mismatch", "name_mismatch").string())) << e;
  EXPECT_TRUE(contains(e, "registers the name 'other_name'")) << e;
}

TEST(CoreRegistry, FileThatIsNotASharedLibrary) {
  const fs::path root = fs::temp_directory_path() / ("spreadmap_registry_" + std::to_string(::getpid()));
  fs::create_directories(root / "contact");
  std::ofstream(root / "contact" / "garbage.so") << "this is text, not ELF\n";
  const std::string e = get_error({root}, "contact", "garbage");
  fs::remove_all(root);
  EXPECT_TRUE(contains(e, "cannot load plugin " + (root / "contact" / "garbage.so").string())) << e;
}

TEST(CoreRegistry, LoadFileChecksTheSameThings) {
  sm::PluginRegistry reg({});
  EXPECT_THROW(reg.load_file(library("abi_mismatch", "abi_mismatch")), sm::PluginError);
  EXPECT_THROW(reg.load_file(library("kind_mismatch", "kind_mismatch"), "contact"), sm::PluginError);
  EXPECT_EQ(std::string(reg.load_file(library("good", "fixture_law"), "contact").descriptor->name), "fixture_law");
}

TEST(CoreRegistry, AFailedLoadLeavesTheRegistryUsable) {
  sm::PluginRegistry reg({fixtures / "abi_mismatch", fixtures / "good"});
  EXPECT_THROW(reg.get("contact", "abi_mismatch"), sm::PluginError);
  EXPECT_THROW(reg.get("contact", "abi_mismatch"), sm::PluginError);  // not cached as loaded
  EXPECT_EQ(reg.get("contact", "fixture_law").id(), "contact/fixture_law");
}

TEST(CoreRegistry, UnknownNameListsTheKindAndSuggestsTheClosest) {
  const std::string e = get_error({fixtures / "good", fixtures / "abi_mismatch"}, "contact", "fixture_lwa");
  EXPECT_TRUE(contains(e, "unknown contact plugin 'fixture_lwa'")) << e;
  EXPECT_TRUE(contains(e, "did you mean 'fixture_law'?")) << e;
  EXPECT_TRUE(contains(e, "available: abi_mismatch, fixture_law")) << e;
  EXPECT_TRUE(contains(e, (fixtures / "good" / "contact").string())) << e;  // where it looked
}

TEST(CoreRegistry, UnknownNameFarFromEverythingSuggestsNothing) {
  const std::string e = get_error({fixtures / "good"}, "contact", "qqqqqqqqqqqq");
  EXPECT_FALSE(contains(e, "did you mean")) << e;
  EXPECT_TRUE(contains(e, "available: fixture_law")) << e;
  const std::string none = get_error({fixtures / "good"}, "surrogate", "bpnn");
  EXPECT_TRUE(contains(none, "unknown surrogate plugin 'bpnn'")) << none;
  EXPECT_TRUE(contains(none, "available: none")) << none;
}

TEST(CoreRegistry, FirstRootWinsAndTheShadowedCopyIsLoggedOnce) {
  LogCapture log;
  sm::PluginRegistry reg({fixtures / "shadow", fixtures / "good"});
  const auto &p = reg.get("contact", "fixture_law");
  EXPECT_EQ(std::string(p.descriptor->version), "2.0.0");
  EXPECT_EQ(fs::canonical(p.file), fs::canonical(library("shadow", "fixture_law")));
  reg.get("contact", "fixture_law");
  const auto lines = log.lines();
  ASSERT_EQ(lines.size(), 1u);
  EXPECT_TRUE(contains(lines[0], "contact/fixture_law")) << lines[0];
  EXPECT_TRUE(contains(
      lines[0], library("shadow", "fixture_law").string() + " shadows " + library("good", "fixture_law").string()))
      << lines[0];
}

TEST(CoreRegistry, RootOrderDecides) {
  sm::PluginRegistry reg({fixtures / "good", fixtures / "shadow"});
  EXPECT_EQ(std::string(reg.get("contact", "fixture_law").descriptor->version), "1.0.0");
}

TEST(CoreRegistry, PluginPathComesFirstThenBesideTheBinary) {
  const fs::path beside = fs::weakly_canonical(fs::path(SPREADMAP_BINARY_DIR) / "lib" / "spreadmap" / "plugins");
  {
    ScopedEnv env("SPREADMAP_PLUGIN_PATH", "/first::/second:");
    const auto roots = sm::PluginRegistry::default_roots();
    ASSERT_EQ(roots.size(), 3u);
    EXPECT_EQ(roots[0], "/first");
    EXPECT_EQ(roots[1], "/second");
    EXPECT_EQ(fs::weakly_canonical(roots[2]), beside);
  }
  {
    ScopedEnv env("SPREADMAP_PLUGIN_PATH", "");
    const auto roots = sm::PluginRegistry::default_roots();
    ASSERT_EQ(roots.size(), 1u);
    EXPECT_EQ(fs::weakly_canonical(roots[0]), beside);
  }
}

TEST(CoreRegistry, PluginPathShadowsTheDefaultRoot) {
  ScopedEnv env("SPREADMAP_PLUGIN_PATH", (fixtures / "shadow").c_str());
  sm::PluginRegistry reg(sm::PluginRegistry::default_roots());
  EXPECT_EQ(std::string(reg.get("contact", "fixture_law").descriptor->version), "2.0.0");
}

TEST(CoreRegistry, InstancesAreMadeAndFreedByThePlugin) {
  sm::PluginRegistry reg({fixtures / "good"});
  const auto &p = reg.get("contact", "fixture_law");
  sm::PluginInstance a(p, "{}");
  ASSERT_NE(a.get(), nullptr);
  EXPECT_EQ(*static_cast<int *>(a.get()), 42);
  sm::PluginInstance b(std::move(a));  // moved-from must not free it a second time (ASan checks)
  EXPECT_EQ(a.get(), nullptr);
  EXPECT_NE(b.get(), nullptr);
  sm::PluginInstance c;
  c = std::move(b);
  EXPECT_EQ(c.plugin(), &p);
}

TEST(CoreRegistry, AFactoryThatRefusesIsAPluginError) {
  sm::PluginRegistry reg({fixtures / "refusing"});
  try {
    sm::PluginInstance i(reg.get("contact", "refusing"), "{}", "scene.contact");
    FAIL() << "no error";
  } catch (const sm::PluginError &e) {
    EXPECT_TRUE(contains(e.what(), "scene.contact: contact/refusing: fixture refuses every parameter set")) << e.what();
  }
}

TEST(CoreRegistry, AFactoryThatThrowsIsAPluginErrorNotACrash) {
  sm::PluginRegistry reg({fixtures / "throwing"});
  try {
    sm::PluginInstance i(reg.get("contact", "throwing"), "{}", "scene.contact");
    FAIL() << "no error";
  } catch (const sm::PluginError &e) {
    EXPECT_TRUE(contains(e.what(), "scene.contact: contact/throwing:")) << e.what();
    EXPECT_TRUE(contains(e.what(), "fixture factory always throws")) << e.what();
    EXPECT_EQ(e.exit_code, sm::exit_plugin);
  }
}
