// What a stage asks of a plugin it is not given the name of (workflow/stage/plugin_needs.hpp): the
// plugin is chosen by what it declares, never by its name.
#include <gtest/gtest.h>
#include <spreadmap/surrogate.hpp>

#include <algorithm>
#include <filesystem>
#include <string>

#include "core/error.hpp"
#include "workflow/stage/plugin_needs.hpp"

namespace sm = spreadmap;
namespace fs = std::filesystem;

namespace {

const fs::path plugins = fs::path(SPREADMAP_BINARY_DIR) / "lib" / "spreadmap" / "plugins";
const fs::path fixtures = SPREADMAP_FIXTURE_DIR;

bool contains(const std::string &text, const std::string &part) { return text.find(part) != std::string::npos; }

}  // namespace

// The metrics plugin is the one whose declared metrics hold the contract (V_s in m^2/s, R_q in m).
TEST(PluginNeeds, TheMetricsPluginIsTheOneThatDeclaresTheContract) {
  sm::PluginRegistry reg({plugins});
  const sm::LoadedPlugin &chosen = sm::contract_metrics_plugin(reg, "the characterise stage");
  const auto gives = sm::declared_metrics(chosen);
  for (const auto &c : sm::metric_contract()) {
    const auto it = std::find_if(gives.begin(), gives.end(), [&](const sm_metric_v1 &m) { return c.name == std::string(m.name); });
    ASSERT_NE(it, gives.end()) << c.name;
    EXPECT_EQ(std::string(it->unit), c.unit) << c.name;
  }
  EXPECT_EQ(sm::contract_columns(), "vs,rq");
}

// A metrics plugin built for ABI 10.1 loads (an older minor of this major) but declares nothing, so
// it is not taken where a stage must count on the contract: the refusal says what was asked for.
TEST(PluginNeeds, AMetricsPluginThatDeclaresNothingIsNotChosenAndTheRefusalSaysWhy) {
  sm::PluginRegistry reg({fixtures / "abi_10_1"});
  const sm::LoadedPlugin &older = reg.get("metrics", "layer");
  EXPECT_TRUE(sm::declared_metrics(older).empty());
  try {
    sm::contract_metrics_plugin(reg, "the characterise stage");
    FAIL() << "chosen without declaring the contract";
  } catch (const sm::PluginError &e) {
    EXPECT_TRUE(contains(e.what(), "the characterise stage needs a metrics plugin that declares the metrics vs "
                                   "and rq; of those installed (layer) none does"))
        << e.what();
  }
}

// Surrogates: the one with a predictive standard deviation where a stage weighs by it; every one, in
// name order, where the train stage is not told which.
TEST(PluginNeeds, SurrogatesAreChosenByWhatTheyGive) {
  sm::PluginRegistry reg({plugins});
  const sm::LoadedPlugin &with_std = sm::surrogate_with_std(reg, "the adaptive design");
  EXPECT_EQ(static_cast<const sm_surrogate_ops_v1 *>(with_std.descriptor->ops)->has_std, 1);
  const auto all = sm::every_surrogate(reg);
  ASSERT_GE(all.size(), 2u);
  EXPECT_TRUE(std::is_sorted(all.begin(), all.end()));
  EXPECT_EQ(sm::first_surrogate(reg, "the map stage"), all.front());
  sm::PluginRegistry empty({fixtures / "abi_10_1"});
  EXPECT_TRUE(sm::every_surrogate(empty).empty());
  try {
    sm::surrogate_with_std(empty, "the adaptive design");
    FAIL() << "a surrogate from nowhere";
  } catch (const sm::PluginError &e) {
    EXPECT_TRUE(contains(e.what(), "the adaptive design needs a surrogate plugin that gives a predictive standard "
                                   "deviation; none is installed"))
        << e.what();
  }
}
