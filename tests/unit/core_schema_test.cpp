// Validation of a YAML section against a parameter schema: every error names the file, the 1-based
// line:column of the offending node and the key path; valid values come out in SI with every
// missing key filled from its default.
#include <gtest/gtest.h>
#include <spreadmap/digest.hpp>
#include <spreadmap/params.hpp>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <yaml-cpp/yaml.h>

#include "core/error.hpp"
#include "core/schema.hpp"

namespace sm = spreadmap;

namespace {

constexpr sm_param_v1 params[] = {
    sm::number("diameter", "m", 1e-6, 0.1, 250e-6, "sphere diameter"),
    sm::number("density", "kg/m^3", 1, 1e5, 4430, "material density"),
    sm::number("restitution", "-", 0, 1, 0.8, "normal restitution"),
    sm::required_number("speed", "m/s", 0, 10, "spreader speed U"),
    sm::integer("count", 0, 1e8, 1600, "number of spheres"),
    sm::boolean("periodic", true, "periodic along y"),
    sm::enumeration("mode", "fast|exact|careful", "exact", "how to compute"),
    sm::text("label", "none", "free text"),
    sm::table("extra", "anything"),
};
const sm::SchemaView schema{params, std::size(params)};

struct Checked {
  nlohmann::json values;
  std::vector<std::string> errors;
};

Checked check(const std::string &yaml) {
  sm::Diagnostics diag;
  Checked c;
  c.values = sm::validate_params(schema, YAML::Load(yaml), "wf.yaml", "scene.powder", diag);
  c.errors = diag.errors();
  return c;
}

bool contains(const std::string &text, const std::string &part) { return text.find(part) != std::string::npos; }

}  // namespace

TEST(CoreSchema, ValidValuesComeOutInSiWithDefaultsFilled) {
  const auto c = check("{speed: 100 mm/s, diameter: 0.25 mm, count: 300, mode: FAST}");
  ASSERT_TRUE(c.errors.empty()) << c.errors.front();
  EXPECT_EQ(c.values["speed"].get<double>(), 0.1);
  EXPECT_EQ(c.values["diameter"].get<double>(), 250e-6);
  EXPECT_EQ(c.values["count"].get<long>(), 300);
  EXPECT_EQ(c.values["mode"], "fast");  // enum choices match case-insensitively, stored as declared
  // defaults, with the JSON type of their parameter type
  EXPECT_EQ(c.values["density"].get<double>(), 4430.0);
  EXPECT_EQ(c.values["restitution"].get<double>(), 0.8);
  EXPECT_TRUE(c.values["periodic"].is_boolean());
  EXPECT_TRUE(c.values["periodic"].get<bool>());
  EXPECT_EQ(c.values["label"], "none");
  EXPECT_TRUE(c.values["extra"].is_null());
  EXPECT_EQ(c.values.size(), std::size(params));
}

TEST(CoreSchema, TablesPassThroughAsJson) {
  const auto c = check("{speed: 1, extra: [{diameter: 1, fraction: 0.5}, {diameter: 2, fraction: 0.5}]}");
  ASSERT_TRUE(c.errors.empty());
  ASSERT_TRUE(c.values["extra"].is_array());
  EXPECT_EQ(c.values["extra"][1]["diameter"].get<double>(), 2.0);
}

TEST(CoreSchema, UnknownKeySuggestsTheClosestAndListsAll) {
  const auto c = check("{speed: 1,\n diametre: 1 mm}");
  ASSERT_EQ(c.errors.size(), 1u);
  const std::string &e = c.errors[0];
  EXPECT_TRUE(contains(e, "wf.yaml:2:2: scene.powder.diametre: unknown key")) << e;
  EXPECT_TRUE(contains(e, "did you mean 'diameter'?")) << e;
  EXPECT_TRUE(contains(e, "known: diameter, density, restitution, speed")) << e;
}

TEST(CoreSchema, UnknownKeyFarFromEveryNameSuggestsNothing) {
  const auto c = check("{speed: 1, zzzzzzzz: 3}");
  ASSERT_EQ(c.errors.size(), 1u);
  EXPECT_FALSE(contains(c.errors[0], "did you mean")) << c.errors[0];
  EXPECT_TRUE(contains(c.errors[0], "known:")) << c.errors[0];
}

TEST(CoreSchema, WrongTypesAreNamed) {
  {
    const auto c = check("{speed: 1, count: 2.5}");
    ASSERT_EQ(c.errors.size(), 1u);
    EXPECT_TRUE(contains(c.errors[0], "wf.yaml:1:19: scene.powder.count: '2.5' is not a whole number")) << c.errors[0];
  }
  {
    const auto c = check("{speed: 1, periodic: maybe}");
    ASSERT_EQ(c.errors.size(), 1u);
    EXPECT_TRUE(contains(c.errors[0], "scene.powder.periodic: 'maybe' is not a boolean")) << c.errors[0];
  }
  {
    const auto c = check("{speed: 1, mode: fats}");
    ASSERT_EQ(c.errors.size(), 1u);
    EXPECT_TRUE(contains(c.errors[0], "'fats' is not one of fast, exact, careful")) << c.errors[0];
    EXPECT_TRUE(contains(c.errors[0], "did you mean 'fast'?")) << c.errors[0];
  }
  {
    const auto c = check("{speed: 1, diameter: [1 mm, 2 mm]}");
    ASSERT_EQ(c.errors.size(), 1u);
    EXPECT_TRUE(contains(c.errors[0], "scene.powder.diameter: expected a number here, found a list")) << c.errors[0];
  }
  {
    const auto c = check("{speed: 1, diameter: big}");
    ASSERT_EQ(c.errors.size(), 1u);
    EXPECT_TRUE(contains(c.errors[0], "'big' is not a number")) << c.errors[0];
  }
}

TEST(CoreSchema, OutOfRangeShowsTheRangeInSi) {
  const auto c = check("{speed: 1, restitution: 1.2, diameter: -250 um}");
  ASSERT_EQ(c.errors.size(), 2u);
  EXPECT_TRUE(contains(c.errors[0], "wf.yaml:1:25: scene.powder.restitution: restitution = 1.2 is outside [0, 1]"))
      << c.errors[0];
  EXPECT_TRUE(contains(c.errors[1], "scene.powder.diameter: diameter = -250 um is outside [1e-06, 0.1] m"))
      << c.errors[1];
}

TEST(CoreSchema, RangeBoundsAreInclusive) {
  const auto c = check("{speed: 10 m/s, restitution: 1, count: 0}");
  EXPECT_TRUE(c.errors.empty());
  EXPECT_EQ(c.values["speed"].get<double>(), 10.0);
}

TEST(CoreSchema, WrongDimensionAndUnknownUnit) {
  const auto c = check("{speed: 3 mm,\n diameter: 250 kg,\n density: 4430 kg/furlong^3}");
  ASSERT_EQ(c.errors.size(), 3u);
  EXPECT_TRUE(contains(c.errors[0], "wf.yaml:1:9: scene.powder.speed: '3 mm' has the dimension of m, expected m/s"))
      << c.errors[0];
  EXPECT_TRUE(contains(c.errors[1], "wf.yaml:2:12: scene.powder.diameter: '250 kg' has the dimension of kg"))
      << c.errors[1];
  EXPECT_TRUE(contains(c.errors[2], "wf.yaml:3:11: scene.powder.density:")) << c.errors[2];
  EXPECT_TRUE(contains(c.errors[2], "unknown unit 'furlong'")) << c.errors[2];
}

TEST(CoreSchema, NanAndInfinityAreRejected) {
  const auto c = check("{speed: .nan, diameter: .inf}");
  ASSERT_EQ(c.errors.size(), 2u);
  EXPECT_TRUE(contains(c.errors[0], "scene.powder.speed: '.nan' is not a finite number")) << c.errors[0];
  EXPECT_TRUE(contains(c.errors[1], "scene.powder.diameter: '.inf' is not a finite number")) << c.errors[1];
}

TEST(CoreSchema, RequiredMissingIsReportedWithAHint) {
  const auto c = check("{diameter: 1 mm}");
  ASSERT_EQ(c.errors.size(), 1u);
  EXPECT_TRUE(contains(c.errors[0], "wf.yaml:1:1: scene.powder.speed: required value missing")) << c.errors[0];
  EXPECT_TRUE(contains(c.errors[0], "add speed: <number in m/s>")) << c.errors[0];
}

TEST(CoreSchema, EveryProblemOfASectionIsCollected) {
  const auto c = check("{diametr: 1, count: x, restitution: 2}");
  EXPECT_EQ(c.errors.size(), 4u);  // unknown key, not a whole number, out of range, speed missing
}

TEST(CoreSchema, SectionThatIsNotAMapping) {
  const auto c = check("[1, 2]");
  ASSERT_FALSE(c.errors.empty());
  EXPECT_TRUE(contains(c.errors[0], "wf.yaml:1:1: scene.powder: expected a mapping of parameters")) << c.errors[0];
}

TEST(CoreSchema, SkippedKeysBelongToTheHost) {
  sm::Diagnostics diag;
  const auto v = sm::validate_params(schema, YAML::Load("{use: roller, speed: 1}"), "wf.yaml", "s", diag, {"use"});
  EXPECT_TRUE(diag.empty());
  EXPECT_FALSE(v.contains("use"));
}

TEST(CoreSchema, ThrowIfAnyCarriesEveryMessageAsInputError) {
  sm::Diagnostics diag;
  sm::validate_params(schema, YAML::Load("{diametr: 1}"), "wf.yaml", "scene.powder", diag);
  try {
    diag.throw_if_any();
    FAIL() << "no error";
  } catch (const sm::InputError &e) {
    EXPECT_EQ(e.exit_code, sm::exit_input);
    EXPECT_TRUE(contains(e.what(), "scene.powder.diametr: unknown key"));
    EXPECT_TRUE(contains(e.what(), "scene.powder.speed: required value missing"));
  }
}

TEST(CoreSchema, JsonAndTableDescriptionsListEveryParameter) {
  const sm_plugin_v1 d = {
      SPREADMAP_PLUGIN_ABI, "contact", "demo",  "1.2.3", "a demo", params, static_cast<uint32_t>(std::size(params)),
      SM_BACKEND_CPU,       nullptr,   nullptr, nullptr};
  const auto j = sm::schema_json(d);
  ASSERT_EQ(j["params"].size(), std::size(params));
  EXPECT_EQ(j["params"][0]["name"], "diameter");
  EXPECT_EQ(j["params"][0]["unit"], "m");
  EXPECT_EQ(j["params"][0]["default"].get<double>(), 250e-6);
  EXPECT_EQ(j["params"][3]["required"], true);
  EXPECT_FALSE(j["params"][3].contains("default"));
  EXPECT_EQ(j["params"][6]["choices"], (nlohmann::json{"fast", "exact", "careful"}));
  const std::string table = sm::describe_schema(d);
  for (const auto &p : params) EXPECT_TRUE(contains(table, p.name)) << p.name;
  EXPECT_TRUE(contains(table, "required"));
}

TEST(CoreSchema, AFileParameterIsResolvedBesideItsYamlFileAndCarriesItsDigest) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("spreadmap_schema_path_" + std::to_string(::getpid()));
  fs::create_directories(dir / "parts");
  std::ofstream(dir / "parts" / "blade.stl") << "solid b\nendsolid b\n";
  constexpr sm_param_v1 with_file[] = {sm::file_path("file", "the part")};
  const sm::SchemaView file_schema{with_file, std::size(with_file)};
  sm::Diagnostics diag;
  const std::string yaml_file = (dir / "wf.yaml").string();
  const auto values =
      sm::validate_params(file_schema, YAML::Load("file: parts/blade.stl"), yaml_file, "scene.spreader", diag);
  EXPECT_TRUE(diag.empty());
  EXPECT_EQ(values["file"], (dir / "parts" / "blade.stl").string());
  EXPECT_EQ(values["file_digest"], sm::content_digest("solid b\nendsolid b\n"));
  sm::validate_params(file_schema, YAML::Load("\nfile: parts/blades.stl"), yaml_file, "scene.spreader", diag);
  ASSERT_EQ(diag.errors().size(), 1u);
  EXPECT_TRUE(contains(diag.errors()[0], yaml_file + ":2:7: scene.spreader.file: no file " +
                                             (dir / "parts" / "blades.stl").string()))
      << diag.errors()[0];
  EXPECT_TRUE(contains(diag.errors()[0], "relative to the folder of the file that names it")) << diag.errors()[0];
  fs::remove_all(dir);
}
