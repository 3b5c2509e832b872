// Which backend runs the DEM: the scene's `backend: auto | cpu | cuda` against what this build and
// this machine offer. Works in every build: without CUDA there are simply no devices.
#pragma once
#include <string>

namespace spreadmap::cuda {

enum class Backend { cpu, cuda };
const char *name_of(Backend backend);  // "cpu" | "cuda"

// What the CUDA runtime reports about this machine, asked once per process.
struct DeviceProbe {
  int count = 0;         // usable CUDA devices
  std::string device;    // name of device 0 when count > 0
  std::string why_none;  // when count == 0: why, in plain words
};

// True when this build carries the CUDA backend (SPREADMAP_ENABLE_CUDA resolved to ON).
bool built_with_cuda();
// True when the engine can run a whole case on the GPU: in every CUDA build (the resident stepper).
bool engine_runs_on_cuda();
const DeviceProbe &probe_devices();
// Number of usable CUDA devices: 0 without CUDA in the build, without a driver or without a device.
int device_count();

// The backend for `requested` ("auto", "cpu" or "cuda"). `message` gets one line for the log (the
// caller prints it once per run). Throws InputError for "cuda" when it cannot be honoured (no device:
// says why and to set scene.backend: cpu or auto) and for any other word.
Backend choose_backend(const std::string &requested, std::string &message);
// The same decision for a given probe and engine capability (what the tests drive).
Backend choose_backend(const std::string &requested, const DeviceProbe &probe, bool engine_ready, std::string &message);

}  // namespace spreadmap::cuda
