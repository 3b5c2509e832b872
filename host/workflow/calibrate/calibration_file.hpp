// A calibration file (`spreadmap calibrate FILE.yaml`, docs/calibration.md): which contact
// parameters to identify and over which ranges, the bulk tests (a scene file each, how its angle is
// measured, and the angle measured on the real powder), the design of the simulations and the
// surrogate that links them. Read and checked whole before anything runs.
#pragma once
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/diagnostics.hpp"
#include "core/registry.hpp"
#include "workflow/calibrate/identify.hpp"

namespace spreadmap::calibrate {

namespace fs = std::filesystem;

enum class Measure { heap_angle, drum_angle };

struct BulkTest {
  std::string name;  // the scene's file stem unless given
  fs::path scene;    // absolute
  Measure measure = Measure::heap_angle;
  double plate_z = 0;                   // heap_angle: the plate's height [m]
  double angle_deg = 0, sigma_deg = 0;  // measured on the real powder; sigma > 0
  bool measured = false;                // an angle was given (else only --at can run)
  Location where;
};

struct CalibrationFile {
  fs::path file;
  std::string name;
  std::string law;                         // the contact plugin of the tests' scenes (the first test's)
  std::vector<ParameterRange> parameters;  // keys of the scenes' contact law
  int levels = 3;                          // full factorial: levels^parameters runs per test
  std::vector<BulkTest> tests;
  std::string model;            // surrogate plugin
  nlohmann::json model_params;  // validated SI, every key
};

// Is this YAML document a calibration file? It has `parameters` and `tests` at its top level.
bool is_calibration_document(const YAML::Node &root);

// Throws InputError with every problem of the file (file:line:col, key, fix) before anything runs.
// The parameters are checked against the contact law of every test's scene (a key it does not have,
// a range outside the law's).
CalibrationFile read_calibration_file(const fs::path &file, PluginRegistry &registry);

}  // namespace spreadmap::calibrate
