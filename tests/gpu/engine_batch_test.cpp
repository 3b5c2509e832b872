// Cases that step at once on one GPU end bitwise as each ends alone: the resident stepper runs on its
// own CUDA stream (cuda/resident_stepper.hpp) and the simulate stage's pool steps each case from its
// own host thread. Six spreading cases (unit/concurrent_cases.hpp) run 2000 steps one after another,
// then all six at once. Needs a CUDA device (label gpu): skipped, saying why, where there is none.
#include <gtest/gtest.h>

#include "gpu/gpu_support.hpp"
#include "unit/concurrent_cases.hpp"

TEST(EngineBatch, CasesSteppingAtOnceOnOneGpuEndAsEachAlone) {
  REQUIRE_CUDA_DEVICE();
  expect_cases_at_once_end_as_alone("cuda", {0.04, 0.07, 0.1, 0.13, 0.16, 0.2}, 2000);
}
