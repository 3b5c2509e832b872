// scene.substrate.roughness (workflow/spreading/substrate_roughness.hpp) and the case set-up on a rough
// substrate (workflow/spreading/layer_feed.hpp): the key parses beside the substrate's law keys and is
// refused, with file:line:column, key and fix, where it cannot run; the set-up's fixed spheres have the
// requested R_q of their tops exactly, stand on the plate, are the same for the same seed, and the
// spreader is raised to the mean plane + its gap; the first heap is fed onto them. The refusals
// through the binary: tests/workflow/data/bad/roughness_*.yaml.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "unit/built_plugins.hpp"
#include "workflow/spreading/scene_section.hpp"
#include "workflow/spreading/substrate_roughness.hpp"
#include "workflow/spreading/case_setup.hpp"
#include "workflow/spreading/coarse_grain.hpp"
#include "workflow/spreading/layer_feed.hpp"

namespace sm = spreadmap;

namespace {

constexpr double um = 1e-6;
const std::string rough =
    "preset: quick\nsubstrate: {friction: 0.3, roughness: {rq: 20 um, correlation_length: 600 um}}\n";

// The scene of `yaml` as `spreadmap validate` resolves it from scene.yaml; its errors, one per line.
std::optional<sm::Scene> resolve(const std::string &yaml, std::string &errors) {
  sm::Workflow wf;
  wf.scene = YAML::Load(yaml);
  wf.scene_file = "scene.yaml";
  sm::Diagnostics diag;
  auto scene = sm::resolve_scene(wf, built_plugins(), diag);
  for (const auto &e : diag.errors()) errors += e + "\n";
  return diag.empty() ? scene : std::nullopt;
}

sm::Scene resolved(const std::string &yaml) {
  std::string errors;
  const auto scene = resolve(yaml, errors);
  EXPECT_EQ(errors, "");
  return scene.value_or(sm::Scene{});
}

bool contains(const std::string &text, const std::string &part) { return text.find(part) != std::string::npos; }

// R_q of the fixed spheres' tops about their mean, and that mean.
std::pair<double, double> tops_rq_and_mean(const sm::engine::ParticleSet &s) {
  double mean = 0, sq = 0;
  for (std::size_t i = 0; i < s.size(); ++i) mean += (s.z[i] + s.radius[i]) / double(s.size());
  for (std::size_t i = 0; i < s.size(); ++i) sq += std::pow(s.z[i] + s.radius[i] - mean, 2);
  return {std::sqrt(sq / double(s.size())), mean};
}

}  // namespace

TEST(Roughness, TheKeyParsesBesideTheSubstratesLawAndRoundTrips) {
  const sm::Scene s = resolved(rough);
  ASSERT_TRUE(s.substrate.roughness.has_value());
  EXPECT_DOUBLE_EQ(s.substrate.roughness->rq, 20 * um);
  EXPECT_DOUBLE_EQ(s.substrate.roughness->correlation_length, 600 * um);
  EXPECT_EQ(s.substrate.roughness->sphere_diameter, 0.0);
  EXPECT_DOUBLE_EQ(s.substrate.law["friction"].get<double>(), 0.3);
  const nlohmann::json json = sm::to_json(s);
  EXPECT_EQ(sm::to_json(sm::scene_from_json(json, "test")).dump(), json.dump());
  EXPECT_DOUBLE_EQ(sm::substrate_sphere_diameter(s), 250 * um) << "the default: the powder's D50";
  EXPECT_DOUBLE_EQ(sm::substrate_sphere_diameter(sm::coarse_grained(
                       resolved("preset: quick\npowder: {coarse_grain: 2}\nsubstrate: {roughness: {rq: 20 um, "
                                "correlation_length: 1.5 mm}}\n"),
                       built_plugins())),
                   500 * um)
      << "coarse grained, the default follows the grains";
  // the flat plate: no roughness in the scene's JSON form, so the hashes of flat scenes stand
  EXPECT_FALSE(sm::to_json(resolved("preset: quick\n"))["substrate"].contains("roughness"));
}

TEST(Roughness, BadValuesAreRefusedWithFileLineKeyAndFix) {
  struct Case {
    std::string roughness, at, key, text, fix;
  };
  const std::vector<Case> cases = {
      {"{rq: -1 um, correlation_length: 600 um}", "-1 um", "scene.substrate.roughness.rq", "outside", ""},
      {"{rq: 20 um, correlation_length: 300 um}", "300 um", "scene.substrate.roughness.correlation_length",
       "300 um is below 2 sphere diameters (2 x 250 um (the powder's D50 by volume))",
       "give correlation_length >= 500 um"},
      {"{rq: 20 um, correlation_length: 10 mm, sphere_diameter: 2 mm}", "2 mm",
       "scene.substrate.roughness.sphere_diameter", "does not fit the domain (30 x 1.25 mm)",
       "give sphere_diameter <= 1250 um"},
      {"{rq: 20 um, correlation_length: 40 mm}", "40 mm", "scene.substrate.roughness.correlation_length",
       "longer than the domain", "give correlation_length <= 30 mm"},
      {"{rq: 0.3 mm, correlation_length: 600 um}", "0.3 mm", "scene.substrate.roughness.rq",
       "not below the spreader's gap (500 um)", "use a smaller rq or a larger spreader gap"},
      {"{rq: 20 um}", "{rq", "scene.substrate.roughness.correlation_length", "required value missing",
       "add correlation_length"},
      {"{rq: 20 um, correlation_lenght: 600 um}", "correlation_lenght", "scene.substrate.roughness.correlation_lenght",
       "unknown key", "did you mean 'correlation_length'?"},
  };
  for (const auto &c : cases) {
    const std::string line = "substrate: {roughness: " + c.roughness + "}";
    std::string errors;
    EXPECT_FALSE(resolve("preset: quick\n" + line + "\n", errors).has_value()) << c.roughness;
    const std::string at = "scene.yaml:2:" + std::to_string(line.find(c.at) + 1) + ": " + c.key + ": ";
    EXPECT_TRUE(contains(errors, at)) << "expected " << at << " in\n" << errors;
    EXPECT_TRUE(contains(errors, c.text)) << errors;
    EXPECT_TRUE(contains(errors, c.fix)) << errors;
  }
  std::string errors;  // fixed spheres step on the CPU only
  EXPECT_FALSE(resolve(rough + "backend: cuda\n", errors).has_value());
  EXPECT_TRUE(contains(errors, "scene.yaml:3:10: scene.backend: backend: cuda cannot run a substrate of spheres"))
      << errors;
  EXPECT_TRUE(contains(errors, "set backend: auto or cpu, or remove substrate.roughness")) << errors;
  errors.clear();  // a misspelt section is pointed at the right name
  EXPECT_FALSE(resolve("preset: quick\nsubstrate: {roughnes: {rq: 20 um}}\n", errors).has_value());
  EXPECT_TRUE(contains(errors, "scene.substrate.roughnes: unknown key")) << errors;
  EXPECT_TRUE(contains(errors, "did you mean 'roughness'?")) << errors;
}

TEST(Roughness, TheSetUpsSpheresHaveTheRequestedRqStandOnThePlateAndRaiseTheSpreader) {
  const sm::Scene s = resolved(rough + "layers: {count: 2, thickness: 50 um}\n");
  const auto substrate = sm::substrate_spheres(s);
  ASSERT_EQ(substrate.size(), 120u * 5u);  // 30 mm x 1.25 mm of 250 um spheres
  EXPECT_EQ(std::count(substrate.fixed.begin(), substrate.fixed.end(), 1), long(substrate.size()));
  const auto [rq, mean] = tops_rq_and_mean(substrate);
  EXPECT_NEAR(rq, 20 * um, 1e-12 * 20 * um) << "the generator scales the field to R_q exactly";
  EXPECT_NEAR(mean, sm::substrate_level(s), 1e-15);
  double lowest = 1;
  for (std::size_t i = 0; i < substrate.size(); ++i) lowest = std::min(lowest, substrate.z[i] - substrate.radius[i]);
  EXPECT_NEAR(lowest, 0.0, 1e-18) << "the lowest sphere stands on the plate";

  const double gap = s.spreader.params["gap"].get<double>();
  EXPECT_DOUBLE_EQ(sm::layer_scene(s, 1).spreader.params["gap"].get<double>(), gap + mean);
  EXPECT_DOUBLE_EQ(sm::layer_scene(s, 2).spreader.params["gap"].get<double>(), gap + mean + 50 * um);

  // the same seed gives the same substrate, another seed another one
  EXPECT_EQ(sm::substrate_spheres(s).z, substrate.z);
  sm::Scene other = s;
  other.powder.seed += 1;
  EXPECT_NE(sm::substrate_spheres(other).z, substrate.z);

  // the flat plate: no spheres, the spreader where it was
  const sm::Scene flat = resolved("preset: quick\n");
  EXPECT_TRUE(sm::substrate_spheres(flat).x.empty());
  EXPECT_EQ(sm::substrate_level(flat), 0.0);
  EXPECT_EQ(sm::to_json(sm::layer_scene(flat, 1)).dump(), sm::to_json(flat).dump());
}

TEST(Roughness, TheFirstHeapIsFedOntoTheSubstrateAboveItsPeaks) {
  const sm::Scene s = resolved(rough);
  const auto substrate = sm::substrate_spheres(s);
  sm::engine::ParticleSet heap;  // three spheres as they settled on the plate, in the heap's place
  for (double x : {8e-3, 9e-3, 10e-3}) {
    heap.x.push_back(x), heap.y.push_back(0.6e-3), heap.z.push_back(125 * um), heap.radius.push_back(125 * um);
    heap.mass.push_back(1e-8);
  }
  const auto fed = sm::fed_onto_bed(sm::layer_scene(s, 1), built_plugins(), "scene.json", substrate, heap);
  ASSERT_EQ(fed.size(), substrate.size() + heap.size());
  double peak = 0;
  for (std::size_t i = 0; i < substrate.size(); ++i) {
    EXPECT_EQ(fed.z[i], substrate.z[i]);
    EXPECT_EQ(fed.fixed[i], 1);
    if (substrate.x[i] + substrate.radius[i] >= 8e-3 - 125 * um &&
        substrate.x[i] - substrate.radius[i] <= 10e-3 + 125 * um)
      peak = std::max(peak, substrate.z[i] + substrate.radius[i]);
  }
  for (std::size_t i = substrate.size(); i < fed.size(); ++i) {
    EXPECT_EQ(fed.fixed[i], 0) << "the powder moves";
    EXPECT_GT(fed.z[i] - fed.radius[i], peak) << "above the highest substrate sphere under the heap";
  }
}
