// A machine (scene.machine): the feed's reservoir filled and levelled, then layer by layer the
// platform drops, the piston rises and the roller spreads from behind the feed over the well into the
// overflow. What must hold: the platform and piston stand where the layout puts them; the powder
// moved with its floor (the lowest sphere over the piston and over the platform rests on it); no
// sphere sinks into a block; every sphere is counted (the reservoir's fill, less the overflow); the
// well gains powder each layer; metrics.csv has a row per layer with its relative density; a layer
// lost is spread again bit for bit while the one before is read back. Bad machines are refused
// naming the key and the fix before anything runs.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "engine/vtp_io.hpp"
#include "workflow/process.hpp"
#include "workflow/run_files.hpp"

namespace fs = std::filesystem;
namespace t = spreadmap::test;

namespace {

const fs::path two_layers = fs::path(SPREADMAP_SOURCE_DIR) / "tests/workflow/data/machine/two_layers.yaml";

// The machine of two_layers.yaml [m].
constexpr double thickness = 400e-6, depth = 2e-3, dosing = 1.5;
constexpr double reservoir_from = 6e-3, reservoir_to = 9e-3, well_from = 10e-3, well_to = 14e-3, lip_to = 15e-3;

struct Floor {
  double lowest_over_piston = 1, lowest_over_platform = 1;  // the lowest sphere bottom over each [m]
  double deepest = -1;  // how deep the deepest sphere sinks into the floor's tops or walls [m]
};

// The floor under layer k: the tops of the blocks along x (the overflow has none), and the walls of
// the two pits.
Floor floor_of(const spreadmap::engine::ParticleSet &p, int k) {
  const double piston = -depth + k * dosing * thickness, platform = -k * thickness;
  Floor f;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double x = p.x[i], bottom = p.z[i] - p.radius[i], r = p.radius[i];
    const bool over_piston = x >= reservoir_from && x < reservoir_to, over_well = x >= well_from && x < well_to;
    const double top = over_piston ? piston : over_well ? platform : x < lip_to ? 0.0 : -1.0;
    f.deepest = std::max(f.deepest, top - bottom);
    if (over_piston) f.lowest_over_piston = std::min(f.lowest_over_piston, bottom);
    if (over_well) f.lowest_over_platform = std::min(f.lowest_over_platform, bottom);
    // below the plates, a sphere beside a pit's wall may not reach into it
    if (p.z[i] < 0 && (over_piston || over_well)) {
      const double wall_lo = over_piston ? reservoir_from : well_from, wall_hi = over_piston ? reservoir_to : well_to;
      f.deepest = std::max({f.deepest, r - (x - wall_lo), r - (wall_hi - x)});
    }
  }
  return f;
}

}  // namespace

TEST(Machine, LayersComeFromTheFeedOntoTheDroppingPlatformAndEverySphereIsCounted) {
  const fs::path dir = fs::temp_directory_path() / ("spreadmap_machine_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  const t::Outcome r = t::run({{"run", two_layers.string(), "--out", dir.string()}, {}, {}, {}});
  ASSERT_EQ(r.exit_code, 0) << r.describe();
  const fs::path c = dir / "cases" / "c000";
  const auto cj = t::json_file(c / "case.json");
  ASSERT_EQ(cj.at("layers").size(), 2u);
  std::size_t spheres = cj.at("particles_start").get<std::size_t>(), removed = 0;
  double well_solid = 0;
  for (int k = 1; k <= 2; ++k) {
    const auto &layer = cj["layers"][k - 1];
    EXPECT_DOUBLE_EQ(layer.at("platform_top").get<double>(), -k * thickness);
    EXPECT_DOUBLE_EQ(layer.at("piston_top").get<double>(), -depth + k * dosing * thickness);
    // every sphere counted: the reservoir's fill less what left the domain (the overflow)
    spheres -= layer.at("removed_strokes").get<std::size_t>();
    EXPECT_EQ(layer.at("particles_start").get<std::size_t>(), spheres);
    spheres -= layer.at("removed").get<std::size_t>();
    removed += layer.at("removed").get<std::size_t>();
    const auto state = spreadmap::engine::read_vtp(c / ("layer_" + std::to_string(k)) / "state.vtp").particles;
    EXPECT_EQ(state.size(), spheres);
    const Floor f = floor_of(state, k);
    std::printf("layer %d: %zu spheres, lowest over the piston %.2f um from it, over the platform %.2f um, "
                "deepest %.3f um into the floor; well solid %.4g mm^3\n",
                k, state.size(), (f.lowest_over_piston - (-depth + k * dosing * thickness)) * 1e6,
                (f.lowest_over_platform + k * thickness) * 1e6, f.deepest * 1e6,
                layer.at("well_solid").get<double>() * 1e9);
    EXPECT_NEAR(f.lowest_over_piston, -depth + k * dosing * thickness, 2e-6) << "the powder did not rise with the piston";
    EXPECT_NEAR(f.lowest_over_platform, -k * thickness, 2e-6) << "the powder does not rest on the platform";
    EXPECT_LT(f.deepest, 2e-6) << "a sphere sinks into the machine";
    EXPECT_GT(layer.at("well_solid").get<double>(), well_solid) << "the well gained no powder";
    well_solid = layer.at("well_solid").get<double>();
    EXPECT_LT(layer.at("reservoir_solid_end").get<double>(), layer.at("reservoir_solid_start").get<double>());
  }
  EXPECT_GT(removed, 0u) << "nothing reached the overflow";
  EXPECT_EQ(cj.at("particles_end").get<std::size_t>(), spheres);
  EXPECT_EQ(t::slurp(c / "state.vtp"), t::slurp(c / "layer_2" / "state.vtp"));

  // metrics.csv: one row per layer, measured on the platform; layer 1's spreader edge is gap + thickness
  const auto cols = t::csv_columns(dir / "metrics.csv");
  ASSERT_EQ(cols.at("layer"), (std::vector<std::string>{"1", "2"}));
  EXPECT_NEAR(std::stod(cols.at("effective_thickness")[0]), 50e-6 + thickness, 1e-12);
  for (const auto &density : cols.at("layer_relative_density")) {
    std::printf("layer relative density %s\n", density.c_str());
    EXPECT_GT(std::stod(density), 0.3);
    EXPECT_LT(std::stod(density), 0.74) << "denser than the densest sphere packing";
  }

  // a lost layer is spread again, bit for bit, from the layer before, which is read back
  const std::string layer_2 = t::slurp(c / "layer_2" / "state.vtp");
  fs::remove_all(c / "layer_2");
  fs::remove(c / "case.json");
  const t::Outcome again = t::run({{"run", two_layers.string(), "--out", dir.string(), "--only", "simulate"}, {}, {}, {}});
  ASSERT_EQ(again.exit_code, 0) << again.describe();
  EXPECT_NE(again.err.find("c000 layer 1: finished before, read back"), std::string::npos) << again.err;
  EXPECT_EQ(t::slurp(c / "layer_2" / "state.vtp"), layer_2) << "layer 2 spread again differs";
  if (!HasFailure()) fs::remove_all(dir);
}

TEST(Machine, BadMachinesAreRefusedNamingTheKeyAndTheFix) {
  const fs::path dir = fs::temp_directory_path() / ("spreadmap_bad_machine_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::string original = t::slurp(two_layers);
  struct Bad {
    std::string from, to, where, what;
  };
  const std::vector<Bad> bad = {
      {"reservoir_depth: 2 mm", "reservoir_depth: 1.2 mm", "scene.machine.reservoir_depth",
       "cannot supply the layers"},
      {"well_length: 4 mm", "well_length: 100 um", "scene.machine.well_length",
       "narrower than the largest sphere"},
      {"start: 0 mm", "start: 4 mm", "scene.spreader.start", "over the reservoir"},
      {"travel: 20 mm", "travel: 15 mm", "scene.spreader.travel", "before the well ends"},
      {"domain: {length: 17 mm}", "domain: {length: 17 mm, periodic_y: false}", "scene.domain",
       "periodic across"},
      {"domain: {length: 17 mm}", "domain: {length: 15.2 mm}", "scene.domain.length", "for the overflow"},
      {"dosing: 1.5,", "dossing: 1.5,", "scene.machine.dossing", "did you mean 'dosing'"},
  };
  for (const Bad &b : bad) {
    std::string text = original;
    ASSERT_NE(text.find(b.from), std::string::npos) << b.from;
    text.replace(text.find(b.from), b.from.size(), b.to);
    std::ofstream(dir / "m.yaml") << text;
    const auto v = t::run({{"validate", (dir / "m.yaml").string()}, {}, {}, {}});
    EXPECT_EQ(v.exit_code, 2) << b.to << "\n" << v.describe();
    EXPECT_NE(v.err.find(b.where), std::string::npos) << "not named: " << b.where << "\n" << v.err;
    EXPECT_NE(v.err.find(b.what), std::string::npos) << "not said: " << b.what << "\n" << v.err;
    EXPECT_NE(v.err.find((dir / "m.yaml").string() + ":"), std::string::npos) << "no file:line\n" << v.err;
  }
  // a dosing below 1 is warned, not refused: the layer cannot fill
  std::string low = original;
  low.replace(low.find("dosing: 1.5,"), 12, "dosing: 0.8,");
  std::ofstream(dir / "m.yaml") << low;
  const auto w = t::run({{"validate", (dir / "m.yaml").string()}, {}, {}, {}});
  EXPECT_EQ(w.exit_code, 0) << w.describe();
  EXPECT_NE(w.err.find("scene.machine.dosing: 0.8 is below 1"), std::string::npos) << w.err;
  fs::remove_all(dir);
}
