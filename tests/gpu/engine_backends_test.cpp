// The GPU backend steps exactly as the CPU does. A spreading case (the quickstart's scene, a settled
// heap of 400 spheres, roller, substrate, periodic strip) runs 3000 steps once on each backend from
// the same heap: the end states are bitwise equal (the same list, the same order of summation, the
// same host-device functions; double and float), and so are the run's counters. A GPU run
// checkpointed halfway and resumed gives the uninterrupted run's bits too. Needs a CUDA device
// (label gpu): skipped, saying why, where there is none.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <unistd.h>

#include "gpu/gpu_support.hpp"
#include "unit/concurrent_cases.hpp"

namespace sm = spreadmap;
namespace fs = std::filesystem;

namespace {

template <class Real> void backends_agree(const std::string &precision) {
  sm::Scene scene = small_spreading_scene(precision);
  scene.backend = "cpu";
  const auto heap = sm::settle_heap<Real>(scene, built_plugins(), "gpu test", "scene.json");
  auto run = [&](const std::string &backend, std::uint64_t steps) {
    sm::Scene s = scene;
    s.backend = backend;
    auto r = sm::make_spreading_run<Real>(s, built_plugins(), heap, "scene.json");
    r->sim.run_steps(steps);
    return r;
  };
  const auto cpu = run("cpu", 3000), gpu = run("cuda", 3000);
  EXPECT_EQ(cpu->sim.backend_name(), "cpu");
  EXPECT_NE(gpu->sim.backend_name().find("cuda"), std::string::npos) << gpu->sim.backend_name();
  EXPECT_EQ(gpu->sim.size(), cpu->sim.size());
  EXPECT_EQ(gpu->sim.removed_count(), cpu->sim.removed_count());
  EXPECT_EQ(gpu->sim.counters().list_builds, cpu->sim.counters().list_builds);
  EXPECT_EQ(gpu->sim.list_entries(), cpu->sim.list_entries());
  const auto a = cpu->sim.state().kinematics_by_id(), b = gpu->sim.state().kinematics_by_id();
  ASSERT_EQ(a.size(), b.size());
  EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(double)), 0) << precision << ": the backends differ";

  // checkpointed halfway on the GPU and resumed on the GPU: the uninterrupted run's bits
  const fs::path path = fs::temp_directory_path() / ("gpu_resume_" + std::to_string(::getpid()) + ".bin");
  auto half = run("cuda", 1500);
  half->sim.save_checkpoint(path);
  sm::Scene s = scene;
  s.backend = "cuda";
  auto resumed = sm::make_spreading_run<Real>(s, built_plugins(), heap, "scene.json");
  resumed->sim.load_checkpoint(path);
  resumed->sim.run_steps(1500);
  fs::remove(path);
  const auto c = resumed->sim.state().kinematics_by_id();
  ASSERT_EQ(c.size(), b.size());
  EXPECT_EQ(std::memcmp(c.data(), b.data(), c.size() * sizeof(double)), 0)
      << precision << ": resume on the GPU differs";
}

}  // namespace

TEST(EngineBackends, GpuStepsBitwiseAsTheCpuInDouble) {
  REQUIRE_CUDA_DEVICE();
  backends_agree<double>("double");
}

TEST(EngineBackends, GpuStepsBitwiseAsTheCpuInFloat) {
  REQUIRE_CUDA_DEVICE();
  backends_agree<float>("float");
}
