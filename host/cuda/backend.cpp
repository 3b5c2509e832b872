#include "cuda/backend.hpp"

#include "core/error.hpp"

#if SPREADMAP_WITH_CUDA
#include <cuda_runtime_api.h>
#endif

namespace spreadmap::cuda {
namespace {

#if SPREADMAP_WITH_CUDA
std::string version_text(int v) { return std::to_string(v / 1000) + "." + std::to_string(v % 1000 / 10); }
#endif

// The CUDA runtime is linked statically and loads the driver (libcuda.so.1) itself on first use, so
// this binary starts on machines without a driver; there cudaGetDeviceCount fails with an error code.
DeviceProbe ask_runtime() {
  DeviceProbe probe;
#if SPREADMAP_WITH_CUDA
  int count = 0;
  const cudaError_t e = cudaGetDeviceCount(&count);
  if (e == cudaSuccess && count > 0) {
    probe.count = count;
    cudaDeviceProp prop{};
    probe.device = cudaGetDeviceProperties(&prop, 0) == cudaSuccess ? prop.name : "device 0";
    return probe;
  }
  int driver = 0, runtime = 0;
  cudaDriverGetVersion(&driver);
  cudaRuntimeGetVersion(&runtime);
  if (e == cudaSuccess || e == cudaErrorNoDevice)
    probe.why_none = "the NVIDIA driver reports no CUDA device on this machine";
  else if (e == cudaErrorInsufficientDriver && driver == 0)
    probe.why_none = "no NVIDIA driver is installed (libcuda.so.1 cannot be loaded)";
  else if (e == cudaErrorInsufficientDriver)
    probe.why_none = "the NVIDIA driver (CUDA " + version_text(driver) + ") is older than this build's CUDA runtime (" +
                     version_text(runtime) + "): CUDA says 'driver version is insufficient'; update the driver";
  else probe.why_none = std::string("CUDA says '") + cudaGetErrorString(e) + "'";
#else
  probe.why_none =
      "this build has no CUDA backend (configure it with SPREADMAP_ENABLE_CUDA=ON where nvcc is installed)";
#endif
  return probe;
}

}  // namespace

const char *name_of(Backend backend) { return backend == Backend::cuda ? "cuda" : "cpu"; }

bool built_with_cuda() {
#if SPREADMAP_WITH_CUDA
  return true;
#else
  return false;
#endif
}

// A CUDA build steps whole cases on the GPU (cuda/resident_stepper.hpp).
bool engine_runs_on_cuda() { return built_with_cuda(); }

const DeviceProbe &probe_devices() {
  static const DeviceProbe probe = ask_runtime();
  return probe;
}

int device_count() { return probe_devices().count; }

Backend choose_backend(const std::string &requested, const DeviceProbe &probe, bool engine_ready,
                       std::string &message) {
  const std::string fix = "\n  set scene.backend: cpu, or auto (the GPU when one can be used, else the CPU)";
  if (requested == "cpu") {
    message = "backend: cpu (as requested)";
    return Backend::cpu;
  }
  if (requested == "auto") {
    if (probe.count > 0 && engine_ready) {
      message = "backend: cuda on " + probe.device + " (auto: a CUDA device is present)";
      return Backend::cuda;
    }
    message = probe.count > 0
                  ? "backend: cpu (auto: CUDA device " + probe.device +
                        " found, but this build's engine runs cases on the CPU only)"
                  : "backend: cpu (auto fell back to the CPU: no CUDA device was found; " + probe.why_none + ")";
    return Backend::cpu;
  }
  if (requested == "cuda") {
    if (probe.count == 0)
      throw InputError("scene.backend: cuda was requested, but no CUDA device was found: " + probe.why_none +
                       fix);
    if (!engine_ready)
      throw InputError("scene.backend: cuda was requested and CUDA device " + probe.device +
                       " is present, but this build's engine runs cases on the CPU only" + fix);
    message = "backend: cuda on " + probe.device + " (as requested)";
    return Backend::cuda;
  }
  throw InputError("scene.backend: '" + requested + "' is not a backend\n  use auto, cpu or cuda");
}

Backend choose_backend(const std::string &requested, std::string &message) {
  if (requested == "cpu") {  // never wakes the CUDA runtime
    message = "backend: cpu (as requested)";
    return Backend::cpu;
  }
  return choose_backend(requested, probe_devices(), engine_runs_on_cuda(), message);
}

}  // namespace spreadmap::cuda
