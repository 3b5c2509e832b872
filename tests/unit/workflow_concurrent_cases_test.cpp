// Cases stepped at once in one process, each from its own thread (the local executor's pool, --jobs),
// end bitwise as each ends alone: the engine's thread teams, the plugins and the case set-up share no
// state between cases. Three spreading cases (concurrent_cases.hpp) on the CPU, each team of the
// test's OMP_NUM_THREADS threads, so that the cases' threads outnumber the cores.
#include <gtest/gtest.h>

#include "unit/concurrent_cases.hpp"

TEST(ConcurrentCases, CpuCasesSteppedAtOnceEndAsEachAlone) {
  expect_cases_at_once_end_as_alone("cpu", {0.05, 0.1, 0.15}, 2000);
}
