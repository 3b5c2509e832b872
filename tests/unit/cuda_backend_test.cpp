// The scene's backend choice (auto | cpu | cuda) against what the build and the machine offer: the
// decision for each case, the sentences the user reads, and that the real probe agrees with itself.
// Holds in every build, with or without CUDA, with or without a GPU.
#include <gtest/gtest.h>

#include <string>

#include "core/error.hpp"
#include "cuda/backend.hpp"

namespace sm = spreadmap;
using sm::cuda::Backend;

namespace {

const sm::cuda::DeviceProbe no_device{0, "", "no NVIDIA driver is installed (libcuda.so.1 cannot be loaded)"};
const sm::cuda::DeviceProbe one_device{1, "NVIDIA H100 80GB HBM3", ""};

std::string refusal(const std::string &requested, const sm::cuda::DeviceProbe &probe, bool engine_ready) {
  std::string message;
  try {
    sm::cuda::choose_backend(requested, probe, engine_ready, message);
  } catch (const sm::InputError &e) {
    EXPECT_EQ(e.exit_code, sm::exit_input);
    return e.what();
  }
  ADD_FAILURE() << "'" << requested << "' was accepted: " << message;
  return "";
}

TEST(CudaBackend, CpuIsAlwaysGranted) {
  std::string message;
  EXPECT_EQ(sm::cuda::choose_backend("cpu", no_device, true, message), Backend::cpu);
  EXPECT_EQ(sm::cuda::choose_backend("cpu", one_device, true, message), Backend::cpu);
  EXPECT_EQ(message, "backend: cpu (as requested)");
}

TEST(CudaBackend, AutoFallsBackToTheCpuWithoutADeviceAndSaysWhy) {
  std::string message;
  EXPECT_EQ(sm::cuda::choose_backend("auto", no_device, true, message), Backend::cpu);
  EXPECT_NE(message.find("fell back to the CPU"), std::string::npos) << message;
  EXPECT_NE(message.find("no CUDA device was found"), std::string::npos) << message;
  EXPECT_NE(message.find("libcuda.so.1"), std::string::npos) << message;
  EXPECT_EQ(message.find('\n'), std::string::npos) << "one line for the log: " << message;
}

TEST(CudaBackend, AutoTakesThePresentDeviceWhenTheEngineRunsOnIt) {
  std::string message;
  EXPECT_EQ(sm::cuda::choose_backend("auto", one_device, true, message), Backend::cuda);
  EXPECT_NE(message.find("NVIDIA H100"), std::string::npos) << message;
  EXPECT_EQ(sm::cuda::choose_backend("auto", one_device, false, message), Backend::cpu);
  EXPECT_NE(message.find("CPU only"), std::string::npos) << message;
}

TEST(CudaBackend, CudaWithoutADeviceIsAnInputErrorThatSaysHowToFixIt) {
  const std::string text = refusal("cuda", no_device, true);
  EXPECT_NE(text.find("scene.backend: cuda"), std::string::npos) << text;
  EXPECT_NE(text.find("no CUDA device was found"), std::string::npos) << text;
  EXPECT_NE(text.find("libcuda.so.1"), std::string::npos) << text;
  EXPECT_NE(text.find("set scene.backend: cpu"), std::string::npos) << text;
  EXPECT_NE(text.find("auto"), std::string::npos) << text;
}

TEST(CudaBackend, CudaIsRefusedWhileTheEngineRunsOnlyOnTheCpu) {
  const std::string text = refusal("cuda", one_device, false);
  EXPECT_NE(text.find("NVIDIA H100"), std::string::npos) << text;
  EXPECT_NE(text.find("CPU only"), std::string::npos) << text;
  std::string message;
  EXPECT_EQ(sm::cuda::choose_backend("cuda", one_device, true, message), Backend::cuda);
}

TEST(CudaBackend, AnUnknownBackendNamesTheChoices) {
  const std::string text = refusal("gpu", one_device, true);
  EXPECT_NE(text.find("'gpu' is not a backend"), std::string::npos) << text;
  EXPECT_NE(text.find("auto, cpu or cuda"), std::string::npos) << text;
}

// The real probe: consistent with the build, and the real choice follows it.
TEST(CudaBackend, ThisMachinesProbeAgreesWithTheChoice) {
  const auto &probe = sm::cuda::probe_devices();
  EXPECT_EQ(sm::cuda::device_count(), probe.count);
  EXPECT_GE(probe.count, 0);
  if (!sm::cuda::built_with_cuda()) {
    EXPECT_EQ(probe.count, 0);
    EXPECT_NE(probe.why_none.find("SPREADMAP_ENABLE_CUDA=ON"), std::string::npos) << probe.why_none;
  }
  std::string message;
  if (probe.count == 0) {
    EXPECT_FALSE(probe.why_none.empty());
    EXPECT_EQ(sm::cuda::choose_backend("auto", message), Backend::cpu);
    EXPECT_NE(message.find("fell back"), std::string::npos) << message;
    EXPECT_THROW(sm::cuda::choose_backend("cuda", message), sm::InputError);
  } else {
    EXPECT_FALSE(probe.device.empty());
    const Backend chosen = sm::cuda::choose_backend("auto", message);
    EXPECT_EQ(chosen, sm::cuda::engine_runs_on_cuda() ? Backend::cuda : Backend::cpu) << message;
  }
  EXPECT_EQ(sm::cuda::choose_backend("cpu", message), Backend::cpu);
}

}  // namespace
