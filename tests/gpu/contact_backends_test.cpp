// The GPU gives the CPU's numbers. On one random packing (2,000 spheres, ~12 contacts each, random
// velocities, spins and contact history), every contact plugin's pair and wall forces, torques and
// updated history, and every spreader's wall-contact records, are computed once by the plugin's CPU
// table and once by its CUDA kernels; they agree to 1e-12 relative in double and 1e-5 in float.
// Needs a CUDA device (label gpu): skipped, saying why, where there is none.
#include <gtest/gtest.h>
#include <spreadmap/contact.hpp>
#include <spreadmap/geometry.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <tuple>
#include <vector>

#include "gpu/gpu_support.hpp"
#include "cuda/device_state.hpp"
#include "cuda/forces.hpp"
#include "gpu/plugin_params.hpp"
#include "gpu/random_packing.hpp"
#include "verification/contact_laws.hpp"

namespace sm = spreadmap;
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// Every value within `rel` of the CPU's, relative to itself or, for a component that nearly cancels,
// to 1e-3 of the array's largest value. Forces must not be trivially zero; a record field may be
// (the blade's vertical surface velocity), and then the GPU's must be zero too.
template <class Real>
void expect_close(const std::vector<Real> &gpu, const std::vector<Real> &cpu, double rel, const std::string &what,
                  bool may_be_zero = false) {
  ASSERT_EQ(gpu.size(), cpu.size()) << what;
  double scale = 0;
  for (Real v : cpu) scale = std::max(scale, std::abs(double(v)));
  if (scale == 0 && may_be_zero) {
    EXPECT_EQ(gpu, cpu) << what;
    return;
  }
  ASSERT_GT(scale, 0) << what << ": all zero on the CPU, nothing compared";
  std::size_t bad = 0;
  double worst = 0;
  for (std::size_t i = 0; i < cpu.size(); ++i) {
    const double ref = std::max(std::abs(double(cpu[i])), 1e-3 * scale);
    const double err = std::abs(double(gpu[i]) - double(cpu[i])) / ref;
    worst = std::max(worst, err);
    if (err > rel) ++bad;
  }
  EXPECT_EQ(bad, 0u) << what << ": " << bad << " of " << cpu.size() << " values differ by more than " << rel
                     << " relative (worst " << worst << ")";
}

template <class Real>
void expect_same_accumulators(const sm::test::Packing<Real> &g, const sm::test::Packing<Real> &c, double rel,
                              const std::string &what) {
  expect_close(g.fx, c.fx, rel, what + " fx");
  expect_close(g.fy, c.fy, rel, what + " fy");
  expect_close(g.fz, c.fz, rel, what + " fz");
  expect_close(g.tx, c.tx, rel, what + " tx");
  expect_close(g.ty, c.ty, rel, what + " ty");
  expect_close(g.tz, c.tz, rel, what + " tz");
}

struct LawCase {
  std::string name;
  json params;
  std::string label;
};

// CTest names end with this (gtest_discover_tests puts the printed parameter in place of the index).
void PrintTo(const LawCase &c, std::ostream *os) { *os << c.label; }

const std::vector<LawCase> &law_cases() {
  static const std::vector<LawCase> cases = {
      {"hooke_slider", json::object(), "hooke_slider_stick"},
      {"hooke_slider", {{"slider", "viscous"}, {"rolling_friction", 0.1}}, "hooke_slider_viscous_rolling"},
      {"hooke_slider", {{"slider", "coulomb"}, {"clamp_normal", true}}, "hooke_slider_coulomb_clamped"},
      {"hooke_history", {{"rolling_friction", 0.05}}, "hooke_history_rolling"},
      {"hertz_mindlin", {{"youngs_modulus", 1e8}}, "hertz_mindlin"},
      {"hertz_mindlin",
       {{"youngs_modulus", 1e8}, {"clamp_normal", true}, {"rolling_friction", 0.1}},
       "hertz_mindlin_clamped"},
  };
  return cases;
}

// The cases above vary each law's parameters; every law of the shared list must have one.
TEST(ContactBackendCases, CoverEveryContactLaw) {
  const auto &cases = law_cases();
  for (const char *name : sm::test::ContactLaws::names())
    EXPECT_TRUE(std::any_of(cases.begin(), cases.end(), [&](const LawCase &c) { return c.name == name; }))
        << name << " has no case in law_cases()";
}

class ContactBackends : public ::testing::TestWithParam<LawCase> {
 protected:
  void SetUp() override {
    REQUIRE_CUDA_DEVICE();
    const auto &plugin = built_plugins().get("contact", GetParam().name);
    law_ = sm::PluginInstance(plugin, sm::test::plugin_params(plugin.descriptor, GetParam().params));
    cpu_ = law_.ops<sm::sm_contact_ops_v1>();
    gpu_ = sm::cuda::contact_kernels(plugin);
    // this instance's history (no rolling spring: the kernels' count; the CPU table's counts the spring's too)
    spec_.history_values = gpu_.ops->history;
  }
  sm::PluginInstance law_;
  const sm::sm_contact_ops_v1 *cpu_ = nullptr;
  sm::cuda::ContactKernels gpu_;
  sm::test::PackingSpec spec_;
};

TEST_P(ContactBackends, PairForcesAndHistoryMatchTheCpuInDouble) {
  auto cpu = sm::test::make_packing<double>(spec_);
  auto gpu = cpu;
  auto cp = cpu.particles();
  auto cl = cpu.pairs();
  cpu_->pairs_f64(law_.get(), &cp, &cl);
  sm::cuda::compute_pair_forces(gpu_, law_.get(), gpu.particles(), gpu.pairs());
  expect_same_accumulators(gpu, cpu, 1e-12, GetParam().label + " pairs");
  if (spec_.history_values) expect_close(gpu.hist, cpu.hist, 1e-12, GetParam().label + " pair history");
}

TEST_P(ContactBackends, PairForcesMatchTheCpuInFloat) {
  auto cpu = sm::test::make_packing<float>(spec_);
  auto gpu = cpu;
  auto cp = cpu.particles();
  auto cl = cpu.pairs();
  cpu_->pairs_f32(law_.get(), &cp, &cl);
  sm::cuda::compute_pair_forces(gpu_, law_.get(), gpu.particles(), gpu.pairs());
  expect_same_accumulators(gpu, cpu, 1e-5, GetParam().label + " float pairs");
}

TEST_P(ContactBackends, WallForcesAndHistoryMatchTheCpuInDouble) {
  auto cpu = sm::test::make_packing<double>(spec_);
  auto gpu = cpu;
  auto cw = sm::test::make_wall_records(cpu, spec_);
  auto gw = cw;
  auto cp = cpu.particles();
  auto cwv = cw.view();
  cpu_->walls_f64(law_.get(), &cp, &cwv);
  sm::cuda::compute_wall_forces(gpu_, law_.get(), gpu.particles(), gw.view());
  expect_same_accumulators(gpu, cpu, 1e-12, GetParam().label + " walls");
  if (spec_.history_values) expect_close(gw.hist, cw.hist, 1e-12, GetParam().label + " wall history");
}

// State resident on the device across evaluations, as a GPU engine keeps it: two evaluations in a row
// (the second one sees the history the first one left on the device) equal two on the CPU.
TEST_P(ContactBackends, ResidentStateCarriesHistoryLikeTheCpu) {
  auto cpu = sm::test::make_packing<double>(spec_);
  auto gpu = cpu;
  auto cp = cpu.particles();
  auto cl = cpu.pairs();
  cpu_->pairs_f64(law_.get(), &cp, &cl);
  cpu_->pairs_f64(law_.get(), &cp, &cl);
  sm::cuda::select_device(0);
  sm::cuda::DeviceParticles<double> dp;
  sm::cuda::DevicePairList<double> dl;
  dp.upload(gpu.particles());
  dl.upload(gpu.pairs(), gpu.n, gpu_.ops->history);
  sm::cuda::launch_pairs(gpu_, law_.get(), dp.view(), dl.view());
  sm::cuda::launch_pairs(gpu_, law_.get(), dp.view(), dl.view());
  sm::cuda::synchronize(0, "two pair evaluations");
  dp.download_accumulators(gpu.particles());
  dl.download_history(gpu.pairs());
  expect_same_accumulators(gpu, cpu, 1e-12, GetParam().label + " resident pairs");
  if (spec_.history_values) expect_close(gpu.hist, cpu.hist, 1e-12, GetParam().label + " resident history");
}

INSTANTIATE_TEST_SUITE_P(EveryContactPlugin, ContactBackends, ::testing::ValuesIn(law_cases()));

struct SpreaderCase {
  std::string name;
  json params;  // z-dependent values are set from the packing in the test
};

void PrintTo(const SpreaderCase &c, std::ostream *os) { *os << c.name; }

class SpreaderBackends : public ::testing::TestWithParam<SpreaderCase> {};

// The spreader cuts 0.3 mm into the top of the packing while moving (t = 2 ms into its travel).
TEST_P(SpreaderBackends, ContactRecordsMatchTheCpuInDouble) {
  REQUIRE_CUDA_DEVICE();
  sm::test::PackingSpec spec;
  spec.history_values = 0;
  auto cpu = sm::test::make_packing<double>(spec);
  cpu.t = 2e-3;
  auto gpu = cpu;
  const double top = *std::max_element(cpu.z.begin(), cpu.z.end());
  const double middle = 0.5 * (cpu.box_hi[0] - cpu.box_lo[0]);
  json params = GetParam().params;
  params["gap"] = top - 0.3e-3;
  params["start"] = middle - 0.05 * 2e-3;  // at the middle at t = 2 ms
  params["U"] = 0.05;
  const auto &plugin = built_plugins().get("spreader", GetParam().name);
  sm::PluginInstance geometry(plugin, sm::test::plugin_params(plugin.descriptor, params));
  const auto *ops = geometry.ops<sm::sm_spreader_ops_v2>();
  const auto kernels = sm::cuda::spreader_kernels(plugin);

  auto cw = sm::test::make_wall_records(cpu, spec);
  auto gw = cw;
  auto cp = cpu.particles();
  auto cwv = cw.view();
  ops->contacts_f64(geometry.get(), &cp, &cwv);
  sm::cuda::compute_geometry_contacts(kernels, geometry.get(), gpu.particles(), gw.view());
  const auto touching = std::count_if(cw.overlap.begin(), cw.overlap.end(), [](double o) { return o > 0; });
  EXPECT_GT(touching, 50) << "the spreader should touch the top layer";
  expect_close(gw.overlap, cw.overlap, 1e-12, GetParam().name + " overlap");
  for (auto [g, c, field] : {std::tuple{&gw.nx, &cw.nx, "nx"},
                             {&gw.ny, &cw.ny, "ny"},
                             {&gw.nz, &cw.nz, "nz"},
                             {&gw.vx, &cw.vx, "vx"},
                             {&gw.vy, &cw.vy, "vy"},
                             {&gw.vz, &cw.vz, "vz"}}) {
    // Only touching records are defined (the others keep what they held, on both backends alike).
    std::vector<double> gt, ct;
    for (std::size_t i = 0; i < cw.overlap.size(); ++i)
      if (cw.overlap[i] > 0) gt.push_back((*g)[i]), ct.push_back((*c)[i]);
    expect_close(gt, ct, 1e-12, GetParam().name + " " + field, true);
  }
}

INSTANTIATE_TEST_SUITE_P(EverySpreaderPlugin, SpreaderBackends,
                         ::testing::Values(SpreaderCase{"roller", {{"diameter", 2e-3}, {"omega", -20.0}}},
                                           SpreaderCase{"blade", {{"thickness", 1e-3}, {"edge_radius", 0.2e-3}}}));

}  // namespace
