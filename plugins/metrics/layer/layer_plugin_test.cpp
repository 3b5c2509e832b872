// metrics/layer through its C boundary, as the host sees it: descriptor, create, evaluate (JSON owned
// by the instance), heightmap, errors as sm_error text, destroy.
#include <dlfcn.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <nlohmann/json.hpp>
#include <numbers>
#include <string>

#include <spreadmap/metric.hpp>

namespace {

class LayerPlugin : public ::testing::Test {
 protected:
  void SetUp() override {
    handle_ = dlopen(SPREADMAP_LAYER_PLUGIN_FILE, RTLD_NOW | RTLD_LOCAL);
    ASSERT_NE(handle_, nullptr) << dlerror();
    auto entry = reinterpret_cast<sm_plugin_entry_v1>(dlsym(handle_, "spreadmap_plugin_v1"));
    ASSERT_NE(entry, nullptr);
    plugin_ = entry();
    ops_ = static_cast<const sm_metrics_ops_v1 *>(plugin_->ops);
  }
  void TearDown() override {
    if (handle_) dlclose(handle_);
  }
  void *handle_ = nullptr;
  const sm_plugin_v1 *plugin_ = nullptr;
  const sm_metrics_ops_v1 *ops_ = nullptr;
};

TEST_F(LayerPlugin, DescribesItself) {
  EXPECT_EQ(plugin_->abi, SPREADMAP_PLUGIN_ABI);
  EXPECT_STREQ(plugin_->kind, "metrics");
  EXPECT_STREQ(plugin_->name, "layer");
  ASSERT_EQ(plugin_->n_params, 6u);
  EXPECT_STREQ(plugin_->params[0].name, "grid");
  EXPECT_STREQ(plugin_->params[0].unit, "m");
  EXPECT_EQ(plugin_->params[0].def, 0.0);
  EXPECT_STREQ(plugin_->params[1].name, "exclude_loose");
  EXPECT_EQ(plugin_->params[1].type, SM_BOOLEAN);
  EXPECT_EQ(plugin_->params[1].def, 1.0);  // spheres in flight are not the layer, by default
  EXPECT_STREQ(plugin_->params[2].name, "segregation");
  EXPECT_EQ(plugin_->params[2].type, SM_BOOLEAN);
  EXPECT_EQ(plugin_->params[2].def, 0.0);  // opt-in: metrics.csv of existing workflows keeps its columns
  EXPECT_STREQ(plugin_->params[3].name, "depth_profile");
  EXPECT_EQ(plugin_->params[3].type, SM_BOOLEAN);
  EXPECT_EQ(plugin_->params[3].def, 0.0);  // opt-in, as segregation
  EXPECT_STREQ(plugin_->params[4].name, "depth_slice");
  EXPECT_STREQ(plugin_->params[4].unit, "m");
  EXPECT_EQ(plugin_->params[4].def, 50e-6);
  EXPECT_STREQ(plugin_->params[5].name, "top_thickness");
  EXPECT_STREQ(plugin_->params[5].unit, "m");
}

// What the plugin declares (ABI 10.2: `gives`, the metrics a stage may count on) is what it gives, with
// the same units, whatever the switches and whether or not the region holds powder; the switched-on
// metrics come on top. The declaration holds the stages' contract: V_s in m^2/s and R_q in m.
TEST_F(LayerPlugin, DeclaresExactlyTheMetricsEveryEvaluationGivesWithTheirUnits) {
  ASSERT_NE(ops_->gives, nullptr);
  ASSERT_EQ(ops_->n_gives, 11u);
  const double r = 50e-6, x = 0.5e-3, y = 0.5e-3, z = r;
  for (const bool empty : {false, true})
    for (const char *params : {R"({"grid": 0, "exclude_loose": true})",
                               R"({"grid": 0, "exclude_loose": true, "segregation": true, "depth_profile": true,
                                   "depth_slice": 25e-6, "top_thickness": 0})"}) {
      sm_layer_input_v1 in{};
      in.n = empty ? 0 : 1;
      in.x = &x, in.y = &y, in.z = &z, in.r = &r;
      in.region[1] = in.region[3] = 1e-3;
      in.speed = 0.1, in.gap = 200e-6;
      sm_error err{};
      void *self = plugin_->create(params, &err);
      ASSERT_NE(self, nullptr) << err.text;
      const char *text = ops_->evaluate(self, &in, &err);
      ASSERT_NE(text, nullptr) << err.text;
      const auto j = nlohmann::json::parse(text);
      for (uint32_t k = 0; k < ops_->n_gives; ++k) {
        const sm_metric_v1 &m = ops_->gives[k];
        ASSERT_TRUE(j["metrics"].contains(m.name)) << m.name << " declared, not given (" << params << ")";
        EXPECT_EQ(j["units"][m.name].get<std::string>(), m.unit) << m.name;
        EXPECT_GT(std::strlen(m.doc), 10u) << m.name;
      }
      if (std::string(params).find("segregation") == std::string::npos) {
        EXPECT_EQ(j["metrics"].size(), ops_->n_gives) << "without switches it gives nothing undeclared: " << text;
      }
      plugin_->destroy(self);
    }
  const auto unit_of = [&](const std::string &name) -> std::string {
    for (uint32_t k = 0; k < ops_->n_gives; ++k)
      if (name == ops_->gives[k].name) return ops_->gives[k].unit;
    return "(not declared)";
  };
  EXPECT_EQ(unit_of("vs"), "m^2/s");
  EXPECT_EQ(unit_of("rq"), "m");
}

// Packing against depth appears only when asked for: its scalars with units, the profile beside the
// metrics. One 100 um sphere on the substrate in 25 um slices: the slice [0, 25 um] holds the cap of
// height 25 um, pi h^2 (3 r - h) / 3 with h = 25 um, r = 50 um.
TEST_F(LayerPlugin, ReportsPackingAgainstDepthOnlyWhenAsked) {
  const double r = 50e-6, x = 0.5e-3, y = 0.5e-3, z = r;
  sm_layer_input_v1 in{};
  in.n = 1;
  in.x = &x, in.y = &y, in.z = &z, in.r = &r;
  in.region[1] = in.region[3] = 1e-3;
  in.speed = in.gap = std::nan("");
  for (const bool asked : {false, true}) {
    sm_error err{};
    void *self = plugin_->create(asked ? R"({"grid": 0, "exclude_loose": true, "depth_profile": true,
                                             "depth_slice": 25e-6, "top_thickness": 0})"
                                       : R"({"grid": 0, "exclude_loose": true})",
                                 &err);
    ASSERT_NE(self, nullptr) << err.text;
    const char *text = ops_->evaluate(self, &in, &err);
    ASSERT_NE(text, nullptr) << err.text;
    const auto j = nlohmann::json::parse(text);
    for (const char *name : {"packing_top", "packing_bulk", "top_thickness"}) {
      EXPECT_EQ(j["metrics"].contains(name), asked) << name;
      EXPECT_EQ(j["units"].contains(name), asked) << name;
    }
    EXPECT_EQ(j.contains("profiles"), asked);
    if (asked) {
      const auto &p = j["profiles"];
      ASSERT_EQ(p["z"].size(), 4u);  // 100 um of sphere in 25 um slices
      EXPECT_EQ(p["units"]["z"], "m");
      EXPECT_EQ(p["units"]["packing"], "-");
      const double h = 25e-6, cap = std::numbers::pi * h * h * (3 * r - h) / 3;
      EXPECT_NEAR(p["packing"][0].get<double>(), cap / (1e-6 * h), 1e-12);
      EXPECT_NEAR(p["z"][0].get<double>(), h / 2, 1e-18);
      EXPECT_EQ(j["units"]["top_thickness"], "m");
    }
    plugin_->destroy(self);
  }
}

// The segregation metrics appear, with their units, only when asked for.
TEST_F(LayerPlugin, ReportsSegregationOnlyWhenAsked) {
  const double r[2] = {10e-6, 20e-6}, x[2] = {0.2e-3, 2e-3}, y[2] = {0.5e-3, 0.5e-3}, z[2] = {10e-6, 20e-6};
  sm_layer_input_v1 in{};
  in.n = 2;
  in.x = x;
  in.y = y;
  in.z = z;
  in.r = r;
  in.region[1] = in.region[3] = 1e-3;  // holds the smaller sphere only
  in.speed = in.gap = std::nan("");
  for (const bool asked : {false, true}) {
    sm_error err{};
    void *self = plugin_->create(asked ? R"({"grid": 0, "exclude_loose": true, "segregation": true})"
                                       : R"({"grid": 0, "exclude_loose": true, "segregation": false})",
                                 &err);
    ASSERT_NE(self, nullptr) << err.text;
    const char *text = ops_->evaluate(self, &in, &err);
    ASSERT_NE(text, nullptr) << err.text;
    const auto j = nlohmann::json::parse(text);
    for (const char *name : {"layer_d10", "layer_d50", "layer_d90", "feed_d10", "feed_d50", "feed_d90", "d10_ratio",
                             "d50_ratio", "d90_ratio", "layer_d50_number", "feed_d50_number", "d50_number_ratio",
                             "fines_diameter", "layer_fines", "feed_fines"}) {
      EXPECT_EQ(j["metrics"].contains(name), asked) << name;
      EXPECT_EQ(j["units"].contains(name), asked) << name;
    }
    if (asked) {
      // Layer: the 20 um sphere; feed by volume (1 : 8): D50 = 40 um.
      EXPECT_DOUBLE_EQ(j["metrics"]["d50_ratio"].get<double>(), 0.5);
      EXPECT_EQ(j["units"]["layer_d50"], "m");
      EXPECT_EQ(j["units"]["d50_ratio"], "-");
      EXPECT_EQ(j["metrics"]["layer_fines"].get<double>(), 0.0);  // the feed's D10 is 20 um: nothing strictly below
    }
    plugin_->destroy(self);
  }
}

TEST_F(LayerPlugin, EvaluatesASphereAndExposesItsHeightMap) {
  sm_error err{};
  void *self = plugin_->create(R"({"grid": 1e-5, "exclude_loose": true})", &err);
  ASSERT_NE(self, nullptr) << err.text;
  const double r = 125e-6, x = 0.5e-3, y = 0.5e-3, z = 20e-6 + r;
  sm_layer_input_v1 in{};
  in.n = 1;
  in.x = &x;
  in.y = &y;
  in.z = &z;
  in.r = &r;
  in.region[1] = in.region[3] = 1e-3;
  in.substrate_z = 20e-6;
  in.speed = 0.1;
  in.gap = std::nan("");
  const char *text = ops_->evaluate(self, &in, &err);
  ASSERT_NE(text, nullptr) << err.text;
  const auto j = nlohmann::json::parse(text);
  EXPECT_NEAR(j["metrics"]["solid_thickness"].get<double>(), 4 * std::numbers::pi / 3 * r * r * r / 1e-6, 1e-18);
  EXPECT_TRUE(j["metrics"]["packing_fraction_gap"].is_null());
  EXPECT_EQ(j["metrics"]["particles_in_region"].get<int>(), 1);
  for (const char *name : {"mean_height", "rq", "vs", "solid_thickness", "packing_fraction", "packing_fraction_gap",
                           "coverage", "largest_bare_patch", "particles_in_region", "cell"})
    EXPECT_TRUE(j["units"].contains(name)) << name;

  uint32_t nx = 0, ny = 0;
  double x0 = 1, y0 = 1, cell = 0;
  const double *h = ops_->heightmap(self, &nx, &ny, &x0, &y0, &cell);
  ASSERT_NE(h, nullptr);
  EXPECT_EQ(nx, 100u);
  EXPECT_EQ(ny, 100u);
  EXPECT_DOUBLE_EQ(cell, 1e-5);
  EXPECT_NEAR(x0, 0.0, 1e-18);
  // The sample nearest the centre sits (cell/2, cell/2) off it.
  const double rho2 = 2 * 0.25 * cell * cell;
  EXPECT_NEAR(h[50 * nx + 50], r + std::sqrt(r * r - rho2), 1e-15);
  EXPECT_EQ(h[0], 0.0);
  plugin_->destroy(self);
}

TEST_F(LayerPlugin, ReportsBadInputAsErrorText) {
  sm_error err{};
  void *self = plugin_->create(R"({"grid": 0, "exclude_loose": true})", &err);
  ASSERT_NE(self, nullptr) << err.text;
  uint32_t nx = 7, ny = 7;
  EXPECT_EQ(ops_->heightmap(self, &nx, &ny, nullptr, nullptr, nullptr), nullptr);  // nothing evaluated yet
  EXPECT_EQ(nx, 0u);
  sm_layer_input_v1 in{};
  in.region[0] = 1e-3;  // x0 > x1
  EXPECT_EQ(ops_->evaluate(self, &in, &err), nullptr);
  EXPECT_NE(err.code, 0);
  EXPECT_NE(std::strstr(err.text, "region"), nullptr) << err.text;
  plugin_->destroy(self);
}

}  // namespace
