// scene.substrate.height_map (workflow/spreading/substrate_height_map.hpp) and its CSV file
// (workflow/spreading/height_map_file.hpp): the grid read in any order and any unit, each malformed file
// refused at its line with the fix, the substrate's tops on the map, and a map changed after the scene
// was resolved refused where it is read again. Through the binary: tests/workflow/data/bad/height_map_*.yaml.
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "core/error.hpp"
#include "unit/built_plugins.hpp"
#include "workflow/spreading/height_map_file.hpp"
#include "workflow/spreading/scene_section.hpp"
#include "workflow/spreading/substrate_roughness.hpp"
#include "workflow/spreading/layer_feed.hpp"

namespace sm = spreadmap;
namespace fs = std::filesystem;

namespace {

constexpr double um = 1e-6;

class HeightMap : public ::testing::Test {
 protected:
  fs::path dir = fs::temp_directory_path() / ("spreadmap_height_map_" + std::to_string(::getpid()));
  void SetUp() override { fs::create_directories(dir); }
  void TearDown() override { fs::remove_all(dir); }

  fs::path write(const std::string &name, const std::string &text) {
    std::ofstream(dir / name) << text;
    return dir / name;
  }
  // The map of `text`, and every error it gave, one per line.
  std::optional<sm::powder::HeightField> read(const std::string &text, std::string &errors) {
    sm::Diagnostics diag;
    auto map = sm::parse_height_map(text, write("map.csv", text), "scene.substrate.height_map", diag);
    for (const auto &e : diag.errors()) errors += e + "\n";
    return map;
  }
  std::optional<sm::Scene> resolve(const std::string &yaml, std::string &errors) {
    sm::Workflow wf;
    wf.scene = YAML::Load(yaml);
    wf.scene_file = (dir / "scene.yaml").string();
    sm::Diagnostics diag;
    auto scene = sm::resolve_scene(wf, built_plugins(), diag);
    for (const auto &e : diag.errors()) errors += e + "\n";
    return diag.empty() ? scene : std::nullopt;
  }
};

bool contains(const std::string &text, const std::string &part) { return text.find(part) != std::string::npos; }

// A 4 x 3 grid of 100 um spacing from (1 mm, 2 mm), h = 2 um * i - 1 um * j, the rows shuffled.
const std::string small_grid =
    "# a measured patch\n"
    "x [mm],y [mm],height [um]\n"
    "1.3,2.2,4\n1.0,2.0,0\n1.1,2.0,2\n1.2,2.0,4\n1.3,2.0,6\n"
    "# the second row\n"
    "1.0,2.1,-1\n1.1,2.1,1\n1.2,2.1,3\n1.3,2.1,5\n1.0,2.2,-2\n1.1,2.2,0\n1.2,2.2,2\n";

}  // namespace

TEST_F(HeightMap, AGridIsReadInAnyOrderWithItsUnits) {
  std::string errors;
  const auto map = read(small_grid, errors);
  ASSERT_TRUE(map) << errors;
  EXPECT_EQ(map->nx, 4u);
  EXPECT_EQ(map->ny, 3u);
  EXPECT_NEAR(map->dx, 100 * um, 1e-15);
  EXPECT_NEAR(map->dy, 100 * um, 1e-15);
  for (std::size_t j = 0; j < 3; ++j)
    for (std::size_t i = 0; i < 4; ++i)
      EXPECT_NEAR(map->h[j * 4 + i], (2.0 * double(i) - double(j)) * um, 1e-18) << i << ", " << j;
  // units in the cells instead of the header; bare numbers under a bare header are metres
  errors.clear();
  const auto cells = read("x,y,height\n0 mm,0 mm,1 um\n50 um,0,2e-6\n0,50 um,3 um\n50 um,50 um,4 um\n", errors);
  ASSERT_TRUE(cells) << errors;
  EXPECT_NEAR(cells->dx, 50 * um, 1e-15);
  EXPECT_NEAR(cells->h[3], 4 * um, 1e-18);
}

TEST_F(HeightMap, AMalformedFileIsRefusedAtItsLineWithTheFix) {
  struct Case {
    std::string text, at, what, fix;
  };
  const std::string head = "x [um],y [um],height [um]\n";
  const std::vector<Case> cases = {
      {"x [um],y [um],heigth [um]\n0,0,1\n", "map.csv:1: ", "unknown column 'heigth'", "did you mean 'height'?"},
      {"x [um],y [um]\n0,0\n10,0\n0,10\n10,10\n", "map.csv:1: ", "no column 'height'", "the columns x, y and height"},
      {head + "0,0,1\n10,0,1\n0,10,1\n", "map.csv: ", "3 points; a grid needs at least 2 x 2", ""},
      {head + "0,0,1\n10,0,1\n0,10,1\n10,10,1\n20,0,1\n",
       "map.csv: ", "1 of the grid's 3 x 2 points are missing, the first at (0.02 mm, 0.01 mm)",
       "give a height at every grid point"},
      {head + "0,0,1\n10,0,1\n0,10,1\n10,10,1\n10,0,2\n",
       "map.csv:6: ", "the point (0.01 mm, 0 mm) is given twice, here and on line 3", "give each grid point once"},
      {head + "0,0,1\n10,0,1\n24,0,1\n0,10,1\n10,10,1\n24,10,1\n", "map.csv:3: ",
       "the point (0.01 mm, 0 mm) is off the grid of 3 x 2 points spaced 0.012 mm along x", "regular grid"},
      {"x [um],y [um],height\n0,0,1\n10,0,1\n0,10,1\n10,10,1\n", "map.csv:2: ", "height 1000 mm is beyond 100 mm",
       "'height [um]'"},
      {head + "0,0,1\n10,0,one\n0,10,1\n10,10,1\n", "map.csv:3: ", "height: ", "a length with its unit"},
      {"x [um],y [um],height [furlong]\n0,0,1\n", "map.csv:1: ", "column 'height': unknown unit 'furlong'", ""},
  };
  for (const auto &c : cases) {
    std::string errors;
    EXPECT_FALSE(read(c.text, errors)) << c.text;
    EXPECT_TRUE(contains(errors, (dir / c.at).string() + "scene.substrate.height_map: ")) << c.at << "\n" << errors;
    EXPECT_TRUE(contains(errors, c.what)) << errors;
    EXPECT_TRUE(contains(errors, c.fix)) << errors;
  }
}

TEST_F(HeightMap, TheSubstratesTopsFollowTheMapAndAChangedMapIsRefused) {
  // a sine of 8 um amplitude along x, 1 mm period, 25 um spacing: 250 um spheres sit on every 10th point
  std::string csv = "x [um],y [um],height [um]\n";
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 40; ++i)
      csv += std::to_string(25 * i) + "," + std::to_string(25 * j) + "," +
             fmt::format("{:.17g}", 8 * std::sin(2 * M_PI * (25.0 * i) / 1000)) + "\n";
  write("surface.csv", csv);
  std::string errors;
  const auto s = resolve("preset: quick\nsubstrate: {height_map: {file: surface.csv}}\n", errors);
  ASSERT_TRUE(s) << errors;
  ASSERT_TRUE(s->substrate.height_map);
  EXPECT_EQ(s->substrate.height_map->file, (dir / "surface.csv").lexically_normal().string());
  const nlohmann::json json = sm::to_json(*s);
  EXPECT_EQ(sm::to_json(sm::scene_from_json(json, "test")).dump(), json.dump());

  const auto substrate = sm::substrate_spheres(*s);
  ASSERT_EQ(substrate.size(), 120u * 5u);  // 30 mm x 1.25 mm of the powder's 250 um
  for (std::size_t k = 0; k < 120; ++k) {  // the tops follow the sine at the centres, 125 um + 250 um k
    const double x = 125 * um + 250 * um * double(k);
    EXPECT_NEAR(substrate.z[k] - substrate.z[0], 8 * um * (std::sin(2 * M_PI * x / 1e-3) - std::sin(M_PI / 4)), 1e-15)
        << k;
  }
  EXPECT_NEAR(sm::substrate_level(*s), substrate.z[0] + substrate.radius[0] - 8 * um * std::sin(M_PI / 4), 1e-15)
      << "the mean plane: the sine's tops average to its middle";

  write("surface.csv", csv + "# edited\n");
  try {
    sm::substrate_spheres(*s);
    ADD_FAILURE() << "a changed map was read";
  } catch (const sm::InputError &e) {
    EXPECT_TRUE(contains(e.what(), "changed since its scene was resolved")) << e.what();
  }

  errors.clear();
  EXPECT_FALSE(
      resolve("preset: quick\nsubstrate: {roughness: {rq: 20 um, correlation_length: 1 mm}, height_map: "
              "{file: surface.csv}}\n",
              errors));
  EXPECT_TRUE(contains(errors, "scene.substrate.height_map: a substrate is either rough")) << errors;
  errors.clear();
  const std::string nowhere = "substrate: {height_map: {file: nowhere.csv}}";
  EXPECT_FALSE(resolve("preset: quick\n" + nowhere + "\n", errors));
  EXPECT_TRUE(contains(errors, fmt::format("scene.yaml:2:{}: scene.substrate.height_map.file: no CSV file",
                                           nowhere.find("nowhere") + 1)))
      << errors;
  errors.clear();
  EXPECT_FALSE(resolve("preset: quick\nbackend: cuda\nsubstrate: {height_map: {file: surface.csv}}\n", errors));
  EXPECT_TRUE(contains(errors, "or remove substrate.height_map")) << errors;
}
