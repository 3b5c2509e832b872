// The typed scene (workflow/spreading/scene_model.hpp): each preset's resolved scene goes JSON -> Scene -> JSON
// unchanged (so cases/cNNN/scene.json and the case hashes stay what they were); a malformed
// scene.json is refused with its file and key named; and the one function that sets design
// variables sets a plugin parameter and a host key, and carries contact.X to the laws that inherit it.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <fstream>

#include "core/error.hpp"
#include "unit/built_plugins.hpp"
#include "workflow/spreading/scene_section.hpp"
#include "workflow/spreading/scene_key.hpp"
#include "workflow/spreading/scene_model.hpp"

namespace sm = spreadmap;
namespace fs = std::filesystem;

namespace {

sm::Scene preset_scene(const std::string &preset) {
  sm::Workflow wf;
  wf.scene = YAML::Load("preset: " + preset);
  wf.scene_file = "scene.yaml";
  sm::Diagnostics diag;
  const auto scene = sm::resolve_scene(wf, built_plugins(), diag);
  diag.throw_if_any();
  EXPECT_TRUE(scene.has_value());
  return *scene;
}

sm::SceneKey key_of(const sm::Scene &scene, const std::string &name) {
  sm::SceneKey key;
  std::string why;
  EXPECT_TRUE(sm::find_scene_key(scene, built_plugins(), name, key, why)) << why;
  return key;
}

// The message of the InputError that reading `text` as a scene file throws ("" when none).
std::string refusal(const std::string &text) {
  const fs::path file = fs::temp_directory_path() / ("scene_model_" + std::to_string(::getpid()) + ".json");
  std::ofstream(file) << text;
  std::string message;
  try {
    sm::read_scene_file(file);
  } catch (const sm::InputError &e) {
    message = e.what();
  }
  fs::remove(file);
  return message;
}

}  // namespace

TEST(SceneModel, EveryPresetsResolvedSceneRoundTripsToTheSameJsonText) {
  for (const std::string preset : {"quick", "standard", "paper", "paper_full"}) {
    const nlohmann::json json = sm::to_json(preset_scene(preset));
    const sm::Scene again = sm::scene_from_json(json, "test");
    EXPECT_EQ(sm::to_json(again).dump(2), json.dump(2)) << preset;
    EXPECT_EQ(again.preset, preset);
  }
}

// The paper preset is a periodic strip of paper_full's scene (docs/paper-scale.md): the same plate,
// travel, spreader and contact, its heap the full roller's spheres per width (to one sphere). The full
// roller is centred on the full width; the strip lies within its half at y_centre 0.
TEST(SceneModel, ThePaperPresetIsAStripOfTheFullWidthWithItsSpheresPerWidth) {
  const sm::Scene strip = preset_scene("paper"), full = preset_scene("paper_full");
  EXPECT_TRUE(strip.domain.periodic_y);
  EXPECT_FALSE(full.domain.periodic_y);
  EXPECT_DOUBLE_EQ(strip.domain.width, 2e-3);
  EXPECT_DOUBLE_EQ(full.domain.width, 70e-3);
  const double per_width = double(full.powder.count) * strip.domain.width / full.domain.width;
  EXPECT_LE(std::abs(double(strip.powder.count) - per_width), 1.0) << per_width;
  EXPECT_DOUBLE_EQ(full.spreader.params["y_centre"].get<double>(), 35e-3);
  EXPECT_DOUBLE_EQ(strip.spreader.params["y_centre"].get<double>(), 0.0);
  nlohmann::json a = sm::to_json(strip), b = sm::to_json(full);
  for (auto *j : {&a, &b}) {
    (*j)["domain"].erase("width"), (*j)["domain"].erase("periodic_y"), (*j)["powder"].erase("count");
    (*j)["spreader"]["params"].erase("y_centre");
    j->erase("preset");
  }
  EXPECT_EQ(a.dump(2), b.dump(2));
}

TEST(SceneModel, TypedValuesAreTheResolvedOnesInSI) {
  const sm::Scene s = preset_scene("quick");
  const nlohmann::json json = sm::to_json(s);
  EXPECT_EQ(s.domain.length, json["domain"]["length"].get<double>());
  EXPECT_EQ(s.powder.count, json["powder"]["count"].get<std::int64_t>());
  EXPECT_EQ(s.precision, sm::Precision::float64);
  EXPECT_EQ(json["precision"], "double");
  EXPECT_EQ(s.contact.params, json["contact"]["params"]);
  EXPECT_EQ(s.spreader.law, json["spreader"]["law"]);
}

TEST(SceneModel, AMalformedSceneFileIsRefusedNamingTheFileAndTheKey) {
  nlohmann::json json = sm::to_json(preset_scene("quick"));
  nlohmann::json missing = json;
  missing["powder"].erase("count");
  std::string m = refusal(missing.dump());
  EXPECT_NE(m.find("scene_model_"), std::string::npos) << m;
  EXPECT_NE(m.find("scene.powder.count: missing"), std::string::npos) << m;

  nlohmann::json wrong = json;
  wrong["domain"]["width"] = "wide";
  m = refusal(wrong.dump());
  EXPECT_NE(m.find("scene.domain.width: expected a number"), std::string::npos) << m;

  nlohmann::json unknown = json;
  unknown["time"]["stepp"] = 1e-6;
  m = refusal(unknown.dump());
  EXPECT_NE(m.find("scene.time.stepp: unknown key"), std::string::npos) << m;

  nlohmann::json law = json;
  law["spreader"]["law"] = 3;
  m = refusal(law.dump());
  EXPECT_NE(m.find("scene.spreader.law: expected an object"), std::string::npos) << m;

  m = refusal("{\"domain\": ");
  EXPECT_NE(m.find("not valid JSON"), std::string::npos) << m;
}

TEST(SceneModel, ADesignValueSetsAPluginParameterAndAHostKey) {
  sm::Scene s = preset_scene("quick");
  sm::apply_scene_value(s, key_of(s, "U"), 0.07);
  EXPECT_EQ(s.spreader.params["U"].get<double>(), 0.07);
  sm::apply_scene_value(s, key_of(s, "powder.count"), 2500.4);  // an integer key: rounded
  EXPECT_EQ(s.powder.count, 2500);
  EXPECT_TRUE(sm::to_json(s)["powder"]["count"].is_number_integer());
  sm::apply_scene_value(s, key_of(s, "time.safety"), 0.2);
  EXPECT_EQ(s.time.safety, 0.2);
  sm::apply_scene_value(s, key_of(s, "precision"), "float");
  EXPECT_EQ(s.precision, sm::Precision::float32);
  sm::apply_scene_value(s, key_of(s, "spreader.friction"), 0.3);  // the particle-spreader law's key
  EXPECT_EQ(s.spreader.law["friction"].get<double>(), 0.3);
  EXPECT_FALSE(s.spreader.params.contains("friction"));
}

TEST(SceneModel, AContactValueReachesTheLawsThatInheritItOnly) {
  sm::Scene s = preset_scene("quick");
  // the quick preset: overlap_max the same in every law, friction the spreader's and substrate's own
  ASSERT_EQ(s.spreader.law["overlap_max"], s.contact.params["overlap_max"]);
  ASSERT_NE(s.spreader.law["friction"], s.contact.params["friction"]);
  const nlohmann::json spreader_friction = s.spreader.law["friction"];
  sm::apply_scene_value(s, key_of(s, "contact.overlap_max"), 2.5e-6);
  sm::apply_scene_value(s, key_of(s, "contact.friction"), 0.4);
  for (const nlohmann::json *law : {&s.contact.params, &s.substrate.law, &s.spreader.law})
    EXPECT_EQ((*law)["overlap_max"].get<double>(), 2.5e-6);
  EXPECT_EQ(s.contact.params["friction"].get<double>(), 0.4);
  EXPECT_EQ(s.spreader.law["friction"], spreader_friction);
}

TEST(SceneModel, ASceneKeyTheSceneLacksIsRefused) {
  sm::Scene s = preset_scene("quick");
  EXPECT_THROW(sm::set_host_key(s, "powder", "colour", 1), sm::InputError);
  EXPECT_THROW(sm::set_host_key(s, "domain", "length", "long"), sm::InputError);
}

TEST(SceneModel, OnlyTopLevelKeysThatChangeTheResultAreDesignVariables) {
  const sm::Scene s = preset_scene("quick");
  sm::SceneKey key;
  std::string why;
  EXPECT_TRUE(sm::find_scene_key(s, built_plugins(), "gravity", key, why));
  EXPECT_FALSE(sm::find_scene_key(s, built_plugins(), "threads", key, why));  // the same case, only faster
  EXPECT_FALSE(sm::find_scene_key(s, built_plugins(), "preset", key, why));   // applied while resolving
}
