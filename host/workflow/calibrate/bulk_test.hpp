// One bulk test at one set of contact parameters: the test's scene loaded, the parameters set on its
// particle-particle law (the walls keep theirs), run to the scene's duration on this thread's cores,
// and its angle measured from the final state (angle_fit.hpp). The result is cached in a JSON file
// so that a calibration stopped and run again never recomputes a finished run.
#pragma once
#include <filesystem>
#include <vector>

#include "core/registry.hpp"
#include "workflow/calibrate/angle_fit.hpp"
#include "workflow/calibrate/calibration_file.hpp"

namespace spreadmap::calibrate {

struct BulkResult {
  AngleFit angle;
  std::size_t particles = 0;
  std::uint64_t steps = 0;
  double wall_seconds = 0;
  bool reused = false;
};

// values: one per parameter of `names`. `record`: the cache file (written atomically when run;
// reused when it holds the same test and parameter values).
BulkResult run_bulk_test(const BulkTest &test, const std::vector<ParameterRange> &names,
                         const std::vector<double> &values, const std::filesystem::path &record,
                         PluginRegistry &registry);

}  // namespace spreadmap::calibrate
