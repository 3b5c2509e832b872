// What the gpu tests share: skipping (saying why) where there is no CUDA device, and the build
// tree's plugins (built_plugins()).
#pragma once
#include <gtest/gtest.h>

#include "cuda/backend.hpp"
#include "unit/built_plugins.hpp"

#define REQUIRE_CUDA_DEVICE()               \
  if (spreadmap::cuda::device_count() == 0) \
  GTEST_SKIP() << "no CUDA device: " << spreadmap::cuda::probe_devices().why_none
