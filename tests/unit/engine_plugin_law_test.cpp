// load_contact_law: a contact law from a plugin for programs that build scenes in code. Parameters
// are checked as in a workflow file (units, defaults, every bad value named with its key and fix),
// and the default search finds this build's plugins through the spreadmap_engine target.
#include <engine/plugin_law.hpp>
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

namespace sm = spreadmap;
using sm::engine::load_contact_law;

namespace {

// The message of the error `load` throws, or "" when it does not throw `Error`.
template <class Error, class Load> std::string error_of(Load load) {
  try {
    load();
  } catch (const Error &e) {
    return e.what();
  }
  return "";
}

bool contains(const std::string &text, const std::string &part) { return text.find(part) != std::string::npos; }

}  // namespace

TEST(PluginLaw, BindsWithUnitsAndDefaults) {
  const auto law =
      load_contact_law("hooke_slider", {{"overlap_max", "5 um"}, {"v_max", "100 mm/s"}, {"restitution", 0.7}});
  EXPECT_EQ(law.id(), "contact/hooke_slider");
  EXPECT_EQ(law.file().parent_path(), std::filesystem::path(SPREADMAP_BINARY_DIR "/lib/spreadmap/plugins/contact"));
  EXPECT_DOUBLE_EQ(law.params().at("overlap_max").get<double>(), 5e-6);
  EXPECT_DOUBLE_EQ(law.params().at("v_max").get<double>(), 0.1);
  EXPECT_EQ(law.params().at("restitution").get<double>(), 0.7) << "a bare number reads back exactly";
  EXPECT_EQ(law.params().at("slider").get<std::string>(), "stick") << "a missing key takes its default";
  EXPECT_EQ(law.params().at("clamp_normal").get<bool>(), false);
  ASSERT_NE(law.law().ops, nullptr);
  ASSERT_NE(law.law().self, nullptr);
  EXPECT_EQ(law.law().ops->history, 0u);

  // The view stays valid when the owner moves; a null parameter object means all defaults.
  auto moved = load_contact_law("hooke_slider", nullptr);
  const auto view = moved.law();
  const auto owner = std::move(moved);
  EXPECT_EQ(owner.law().self, view.self);
  EXPECT_EQ(owner.params().at("restitution").get<double>(), 0.8);
}

TEST(PluginLaw, RefusesBadParametersNamingTheKey) {
  const auto misspelt = error_of<sm::InputError>([] { load_contact_law("hooke_slider", {{"restitutoin", 0.5}}); });
  EXPECT_TRUE(contains(misspelt, "error: load_contact_law(\"hooke_slider\"): params.restitutoin: unknown key"))
      << misspelt;
  EXPECT_TRUE(contains(misspelt, "did you mean 'restitution'?")) << misspelt;

  const auto dimension = error_of<sm::InputError>([] { load_contact_law("hooke_slider", {{"overlap_max", "5 m/s"}}); });
  EXPECT_TRUE(contains(dimension, "params.overlap_max: '5 m/s' has the dimension of")) << dimension;

  const auto range = error_of<sm::InputError>([] { load_contact_law("hooke_slider", {{"restitution", 1.5}}); });
  EXPECT_TRUE(contains(range, "params.restitution: restitution = 1.5 is outside")) << range;

  const auto shape = error_of<sm::InputError>([] { load_contact_law("hooke_slider", nlohmann::json::array({0.5})); });
  EXPECT_TRUE(contains(shape, "params: expected a JSON object of parameters, found [0.5]")) << shape;
}

TEST(PluginLaw, RefusesAnUnknownPluginNamingTheFoldersSearched) {
  const auto typo = error_of<sm::PluginError>([] { load_contact_law("hooke_slidr"); });
  EXPECT_TRUE(contains(typo, "unknown contact plugin 'hooke_slidr'")) << typo;
  EXPECT_TRUE(contains(typo, "did you mean 'hooke_slider'?")) << typo;

  // Explicit folders are the only ones searched.
  const std::filesystem::path empty = std::filesystem::path(SPREADMAP_BINARY_DIR) / "no_plugins_here";
  const auto elsewhere = error_of<sm::PluginError>([&] { load_contact_law("hooke_slider", {}, {empty}); });
  EXPECT_TRUE(contains(elsewhere, "available: none (searched " + (empty / "contact").string() + ")")) << elsewhere;
}
