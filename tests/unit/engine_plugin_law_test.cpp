// load_contact_law: a contact law from a plugin for programs that build scenes in code. Parameters
// are checked as in a workflow file (units, defaults, every bad value named with its key and fix),
// and the default search finds this build's plugins through the spreadmap_engine target.
#include <engine/plugin_law.hpp>
#include <engine/simulation.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

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
  EXPECT_EQ(sm::engine::law_history(law.law()), 0u) << "no rolling spring: no history";
  EXPECT_EQ(law.law().ops->history, 3u) << "the most an instance keeps: the rolling spring's";

  // The view stays valid when the owner moves; a null parameter object means all defaults.
  auto moved = load_contact_law("hooke_slider", nullptr);
  const auto view = moved.law();
  const auto owner = std::move(moved);
  EXPECT_EQ(owner.law().self, view.self);
  EXPECT_EQ(owner.params().at("restitution").get<double>(), 0.8);
}

TEST(PluginLaw, RefusesBadParametersNamingTheKey) {
  const auto misspelt = error_of<sm::InputError>([] { load_contact_law("hooke_slider", {{"restitutoin", 0.5}}); });
  EXPECT_TRUE(contains(misspelt, "load_contact_law(\"hooke_slider\"): params.restitutoin: unknown key"))
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

namespace {

// Three spheres in a row along x on a floor plane, barely touching, stepped `steps` times (one thread:
// below the engine's parallel size); their positions, velocities and spins, in that order, at the end.
std::vector<double> row_on_floor(const sm::engine::ContactLaw &law, std::uint64_t steps,
                            std::array<double, 3> gravity = {0, 0, -9.81}, bool pairs_once = true) {
  sm::engine::Settings s;
  s.gravity = gravity;
  s.pairs_once = pairs_once;
  sm::engine::Simulation<double> sim({{0, 0, 0}, {0.002, 0.002, 0.002}, {true, true, false}}, law, s);
  sim.add_plane_wall({{0, 0, 0}, {0, 0, 1}, {0, 0, 0}, law});
  sm::engine::ParticleSet p;
  const double r = 125e-6;
  for (int k = 0; k < 3; ++k) {
    p.x.push_back(0.001 + 1.999 * r * k);
    p.y.push_back(0.001);
    p.z.push_back(r);
    p.radius.push_back(r);
  }
  sim.add_particles(p, 4430);
  sim.run_steps(steps);
  std::vector<double> out;
  const auto &a = sim.arrays();
  for (const auto *column : {&a.x, &a.y, &a.z, &a.vx, &a.vy, &a.vz, &a.wx, &a.wy, &a.wz})
    out.insert(out.end(), column->begin(), column->begin() + 3);
  return out;
}

}  // namespace

// A plugin built for ABI 10.0 (tests/unit/core.cmake) has no history_of in its ops table: this host
// reads the table's own count and steps the law bit for bit as the plugin of this build does.
TEST(PluginLaw, APluginOfTheOlderMinorAbiLoadsAndStepsBitForBit) {
  const nlohmann::json params = {{"friction", 0.5}, {"rolling_friction", 0.05}};
  const std::filesystem::path older = std::filesystem::path(SPREADMAP_FIXTURE_DIR) / "abi_10_0";
  const auto old_law = load_contact_law("hooke_history", params, {older});
  const auto new_law = load_contact_law("hooke_history", params);
  ASSERT_EQ(old_law.file().parent_path(), older / "contact");
  EXPECT_EQ(old_law.law().abi_minor, 0u);
  EXPECT_EQ(new_law.law().abi_minor, SPREADMAP_PLUGIN_ABI_MINOR);
  EXPECT_EQ(sm::engine::law_history(old_law.law()), 3u);
  EXPECT_EQ(sm::engine::law_history(new_law.law()), 3u);
  const std::array<double, 3> slope{2, 0, -9.81};  // steeper than mu_r: they roll, sliding friction and rolling torque act
  EXPECT_EQ(row_on_floor(old_law.law(), 3000, slope), row_on_floor(new_law.law(), 3000, slope));

  // what 10.1 added is refused by the older build, naming the version it needs
  const auto refused = error_of<sm::PluginError>([&] {
    load_contact_law("hooke_history", {{"rolling_friction", 0.1}, {"rolling_model", "epsd"}}, {older});
  });
  EXPECT_TRUE(contains(refused, "rolling_model epsd needs plugin ABI 10.1")) << refused;
}

// hertz_mindlin with DMT cohesion and the rolling spring keeps 6 values of history a contact, all of
// which mirror (ABI 10.4): each pair evaluated once steps the row bit for bit as every list entry
// evaluated with its own history.
TEST(PluginLaw, ALawWhoseHistoryMirrorsStepsBitForBitWithEachPairOnce) {
  const auto law = load_contact_law("hertz_mindlin", {{"youngs_modulus", "26 MPa"},
                                                      {"friction", 0.5},
                                                      {"rolling_friction", 0.1},
                                                      {"rolling_model", "epsd"},
                                                      {"surface_energy", "0.1 mJ/m^2"},
                                                      {"pull_off", "dmt"}});
  EXPECT_EQ(sm::engine::law_history(law.law()), 6u);
  EXPECT_TRUE(sm::engine::law_pairs_once(law.law()));
  const std::array<double, 3> slope{2, 0, -9.81};
  const auto every = row_on_floor(law.law(), 3000, slope, false), once = row_on_floor(law.law(), 3000, slope, true);
  EXPECT_EQ(every, once);
  EXPECT_GT(std::abs(once[9]), 1e-3) << "the spheres move: the test compares forces, not rest";
}

// hooke_slider keeps no history of its own: with the rolling spring its 3 values are the spring's,
// which mirror, so it takes the once loop too, with the same bits as every entry.
TEST(PluginLaw, ALawWhoseOnlyHistoryIsTheRollingSpringStepsBitForBitWithEachPairOnce) {
  const auto law = load_contact_law(
      "hooke_slider", {{"friction", 0.5}, {"rolling_friction", 0.1}, {"rolling_model", "epsd"}, {"restitution", 0.3}});
  EXPECT_EQ(sm::engine::law_history(law.law()), 3u);
  EXPECT_TRUE(sm::engine::law_pairs_once(law.law()));
  const std::array<double, 3> slope{2, 0, -9.81};
  const auto every = row_on_floor(law.law(), 3000, slope, false), once = row_on_floor(law.law(), 3000, slope, true);
  EXPECT_EQ(every, once);
  EXPECT_GT(std::abs(once[9]), 1e-3) << "the spheres move: the test compares forces, not rest";
}

// A law built for ABI 10.2 has no queue functions (10.3): this host hands it the whole list and the
// wall's records, without the engine's schedule (the list's mirror and the threads stay the engine's),
// and its loop over every entry gives the bits of the queues that evaluate each pair once.
TEST(PluginLaw, ALawBuiltBeforeTheQueuesStepsBitForBitThroughItsWholeListLoop) {
  const nlohmann::json params = {{"friction", 0.5}, {"rolling_friction", 0.05}};
  const std::filesystem::path older = std::filesystem::path(SPREADMAP_FIXTURE_DIR) / "abi_10_2";
  const auto old_law = load_contact_law("hooke_slider", params, {older});
  const auto new_law = load_contact_law("hooke_slider", params);
  ASSERT_EQ(old_law.file().parent_path(), older / "contact");
  EXPECT_EQ(old_law.law().abi_minor, 2u);
  EXPECT_EQ(new_law.law().abi_minor, SPREADMAP_PLUGIN_ABI_MINOR);
  const std::array<double, 3> slope{2, 0, -9.81};
  const auto before = row_on_floor(old_law.law(), 3000, slope), now = row_on_floor(new_law.law(), 3000, slope);
  EXPECT_EQ(before, now);
  EXPECT_GT(std::abs(now[9]), 1e-3) << "the spheres move: the test compares forces, not rest";
}

// Through the engine (wall and pair records with the spring's history): on a slope flatter than mu_r the
// rolling spring brings the spheres to rest, where the constant torque lets them creep at its
// regularisation's speed (5 g sin(theta) dt, tests/verification/contact_friction_test.cpp).
TEST(PluginLaw, TheRollingSpringHoldsSpheresOnASlopeWhereTheConstantTorqueCreeps) {
  const double mu_r = 0.1, theta = std::atan(0.5 * mu_r), g = 9.81;
  const std::array<double, 3> tilted{g * std::sin(theta), 0, -g * std::cos(theta)};
  const nlohmann::json constant = {{"friction", 0.5}, {"rolling_friction", mu_r}, {"restitution", 0.3}};
  nlohmann::json spring = constant;
  spring["rolling_model"] = "epsd";
  const auto epsd = load_contact_law("hooke_history", spring);
  EXPECT_EQ(sm::engine::law_history(epsd.law()), 6u);
  const std::uint64_t steps = 40000;
  const auto held = row_on_floor(epsd.law(), steps, tilted);
  const auto creeping = row_on_floor(load_contact_law("hooke_history", constant).law(), steps, tilted);
  for (int k = 0; k < 3; ++k) {
    EXPECT_LT(std::abs(held[9 + k]), 1e-9) << "sphere " << k << " at rest: v_x " << held[9 + k];
    EXPECT_GT(creeping[9 + k], 1e-7) << "sphere " << k << " creeps: v_x " << creeping[9 + k];
  }
}
