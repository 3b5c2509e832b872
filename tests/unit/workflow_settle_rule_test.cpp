// The settling rule (workflow/spreading/settle_rule.hpp): settle_fraction 1 ends settling once every
// sphere is slower than settle_speed, a smaller fraction lets (1 - fraction) of them move on; a powder
// section without the key settles as before and writes the scene (and its hashes) as before.
#include <gtest/gtest.h>

#include <vector>

#include "workflow/spreading/scene_model.hpp"
#include "workflow/spreading/settle_rule.hpp"

namespace sm = spreadmap;

namespace {

// n spheres at rest but for `moving` of them, which fall at `speed` [m/s].
struct Velocities {
  std::vector<double> vx, vy, vz;
  Velocities(std::size_t n, std::size_t moving, double speed) : vx(n, 0.0), vy(n, 0.0), vz(n, 0.0) {
    for (std::size_t i = 0; i < moving; ++i) vz[i * 7 % n] = -speed;
  }
  bool settling(const sm::SettleRule &rule) const { return sm::still_settling(rule, vx, vy, vz); }
};

}  // namespace

TEST(SettleRule, EverySphereMustRestUnlessAFractionIsGiven) {
  const sm::SettleRule every{0, 1, 1e-3, 1}, most{0, 1, 1e-3, 0.99};
  const Velocities rattler(100, 1, 0.5), two(100, 2, 0.5), at_rest(100, 0, 0.0);
  EXPECT_TRUE(rattler.settling(every)) << "one sphere bouncing at 0.5 m/s holds the bed settling";
  EXPECT_FALSE(rattler.settling(most)) << "99 of 100 at rest: settled";
  EXPECT_TRUE(two.settling(most)) << "98 of 100 at rest is not 99 %";
  EXPECT_FALSE(at_rest.settling(every));
  // a sphere at exactly settle_speed is not faster than it
  EXPECT_FALSE(Velocities(100, 1, 1e-3).settling(every));
  EXPECT_TRUE(Velocities(100, 1, 1.0000001e-3).settling(every));
  // fewer spheres than one in (1 - fraction): none may move
  EXPECT_TRUE(Velocities(50, 1, 0.5).settling(most));
}

TEST(SettleRule, TheDefaultFractionIsLeftOutOfTheSceneSoItsHashesStay) {
  sm::Scene scene;
  scene.contact.params = nlohmann::json::object();
  scene.spreader.params = scene.spreader.law = scene.substrate.law = nlohmann::json::object();
  nlohmann::json json = sm::to_json(scene);
  EXPECT_FALSE(json["powder"].contains("settle_fraction")) << "at 1, as scene files were written before it";
  EXPECT_EQ(sm::scene_from_json(json, "test").powder.settle_fraction, 1.0);
  scene.powder.settle_fraction = 0.99;
  json = sm::to_json(scene);
  EXPECT_EQ(json["powder"]["settle_fraction"], 0.99);
  EXPECT_EQ(sm::scene_from_json(json, "test").powder.settle_fraction, 0.99);
}
