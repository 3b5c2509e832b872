// What the gpu tests share: skipping (saying why) where there is no CUDA device, and the build
// tree's plugins.
#pragma once
#include <gtest/gtest.h>

#include <filesystem>

#include "core/registry.hpp"
#include "cuda/backend.hpp"

#define REQUIRE_CUDA_DEVICE()               \
  if (spreadmap::cuda::device_count() == 0) \
  GTEST_SKIP() << "no CUDA device: " << spreadmap::cuda::probe_devices().why_none

inline spreadmap::PluginRegistry &registry() {
  static spreadmap::PluginRegistry r({std::filesystem::path(SPREADMAP_BINARY_DIR) / "lib" / "spreadmap" / "plugins"});
  return r;
}
