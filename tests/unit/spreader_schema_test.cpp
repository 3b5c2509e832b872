// Both spreader plugins: schema lint (names, ranges, defaults, units, docs), and the built
// modules through their C descriptor exactly as the host loads them.
#include <dlfcn.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <regex>
#include <set>
#include <string>
#include <vector>

#include "plugins/spreader/blade/blade.hpp"
#include "plugins/spreader/roller/roller.hpp"
#include "unit/spreader_values.hpp"

namespace sm = spreadmap;

namespace {

template <std::size_t N> void lint(const sm_param_v1 (&params)[N], const char *plugin) {
  const std::regex snake("[a-z][a-z0-9_]*");
  const std::set<std::string> known_units = {"m", "m/s", "rad/s", "-"};
  std::set<std::string> names;
  for (const auto &p : params) {
    SCOPED_TRACE(std::string(plugin) + "." + p.name);
    // U is the documented exception to snake_case: a symbol users type every day, like omega.
    EXPECT_TRUE(std::regex_match(p.name, snake) || std::string(p.name) == "U");
    EXPECT_TRUE(names.insert(p.name).second) << "duplicate name";
    ASSERT_NE(p.unit, nullptr);
    EXPECT_TRUE(known_units.count(p.unit)) << "unit " << p.unit;
    ASSERT_NE(p.doc, nullptr);
    EXPECT_GT(std::strlen(p.doc), 10u);
    if (p.type == SM_NUMBER || p.type == SM_INTEGER) {
      EXPECT_FALSE(std::isnan(p.min) || std::isnan(p.max));
      EXPECT_LT(p.min, p.max);
      if (!p.required) {
        EXPECT_GE(p.def, p.min);
        EXPECT_LE(p.def, p.max);
      }
    }
  }
}

const sm_plugin_v1 *load(const std::string &name) {
  const std::string path = std::string(SPREADMAP_BINARY_DIR) + "/lib/spreadmap/plugins/spreader/" + name + ".so";
  void *handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);  // kept open until exit, as the host does
  if (!handle) ADD_FAILURE() << dlerror();
  if (!handle) return nullptr;
  auto entry = reinterpret_cast<sm_plugin_entry_v1>(dlsym(handle, "spreadmap_plugin_v1"));
  if (!entry) ADD_FAILURE() << "no spreadmap_plugin_v1 in " << path;
  return entry ? entry() : nullptr;
}

}  // namespace

TEST(SpreaderSchema, RollerParamsPassLint) { lint(sm::spreader::Roller::params, "spreader/roller"); }
TEST(SpreaderSchema, BladeParamsPassLint) { lint(sm::spreader::Blade::params, "spreader/blade"); }

TEST(SpreaderSchema, RollerModuleComputesContactsThroughItsOps) {
  const sm_plugin_v1 *d = load("roller");
  ASSERT_NE(d, nullptr);
  EXPECT_EQ(d->abi, SPREADMAP_PLUGIN_ABI);
  EXPECT_STREQ(d->kind, "spreader");
  EXPECT_STREQ(d->name, "roller");
  EXPECT_EQ(d->n_params, std::size(sm::spreader::Roller::params));
  nlohmann::json values = sm::test::schema_defaults(sm::spreader::Roller::params);
  values["omega"] = 20.0;
  sm_error err{};
  void *self = d->create(values.dump().c_str(), &err);
  ASSERT_NE(self, nullptr) << err.text;
  const auto *ops = static_cast<const sm::sm_spreader_ops_v2 *>(d->ops);
  sm::sm_spreader_description_v2 description{};
  ops->describe(self, &description);
  EXPECT_DOUBLE_EQ(description.duration, 26e-3 / 0.1);
  EXPECT_DOUBLE_EQ(ops->max_surface_speed(self), 0.1 + 20.0 * 5e-3);

  // Two spheres: one under the roller bottom (overlap 10 um), one far away.
  std::vector<double> x{6e-3, 30e-3}, y{0, 0}, z{0.5e-3 - 125e-6 + 10e-6, 0.2e-3}, zero(2, 0.0), r(2, 125e-6);
  std::vector<double> f(2, 0.0), ov(2, -1), nx(2), ny(2), nz(2), vx(2), vy(2), vz(2);
  sm::Particles<double> p{};
  p.n = 2;
  p.x = x.data();
  p.y = y.data();
  p.z = z.data();
  p.vx = p.vy = p.vz = p.wx = p.wy = p.wz = zero.data();
  p.r = r.data();
  p.m = r.data();
  p.fx = p.fy = p.fz = p.tx = p.ty = p.tz = f.data();
  p.t = 0.0;
  sm::WallContacts<double> w{2, ov.data(), nx.data(), ny.data(), nz.data(), vx.data(), vy.data(), vz.data(), nullptr};
  ops->contacts_f64(self, &p, &w);
  EXPECT_NEAR(ov[0], 10e-6, 1e-15);
  EXPECT_NEAR(nz[0], -1.0, 1e-15);
  EXPECT_NEAR(vx[0], 0.0, 1e-14);  // omega = U/R: the bottom is at rest
  EXPECT_EQ(ov[1], 0.0);

  sm::sm_spreader_pose_v2 pose;
  ops->pose(self, 0.1, &pose);
  EXPECT_NEAR(pose.reference[0], 6e-3 + 0.01, 1e-15);

  // touches(): the sphere under the roller bottom, at rest (t < 0) as when moving; not the far one.
  const double under[3] = {x[0], y[0], z[0]}, far[3] = {x[1], y[1], z[1]};
  EXPECT_EQ(ops->touches(self, -1.0, under, r[0]), 1);
  EXPECT_EQ(ops->touches(self, -1.0, under, r[0] - 11e-6), 0);  // 1 um short of the surface
  EXPECT_EQ(ops->touches(self, -1.0, far, r[1]), 0);
  d->destroy(self);
}

TEST(SpreaderSchema, BladeModuleRefusesAnOversizedEdgeWithASentence) {
  const sm_plugin_v1 *d = load("blade");
  ASSERT_NE(d, nullptr);
  EXPECT_STREQ(d->name, "blade");
  nlohmann::json values = sm::test::schema_defaults(sm::spreader::Blade::params);
  sm_error err{};
  void *ok = d->create(values.dump().c_str(), &err);
  ASSERT_NE(ok, nullptr) << err.text;
  d->destroy(ok);
  values["edge_radius"] = 0.8e-3;
  EXPECT_EQ(d->create(values.dump().c_str(), &err), nullptr);
  EXPECT_NE(err.code, 0);
  EXPECT_NE(std::string(err.text).find("edge_radius"), std::string::npos) << err.text;
}
