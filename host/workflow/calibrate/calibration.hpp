// The calibration run: every bulk test simulated over a full-factorial design of the parameter box
// (bulk_test.hpp, each run cached), one surrogate per test fitted to its angles (the model the file
// names, by default the first that gives a predictive standard deviation, with its leave-one-out error
// in degrees), and the parameters identified from the measured angles (identify.hpp). Writes
// <out>/calibration.json.
#pragma once
#include <filesystem>
#include <nlohmann/json_fwd.hpp>

#include "core/registry.hpp"
#include "workflow/calibrate/calibration_file.hpp"

namespace spreadmap::calibrate {

// Returns what calibration.json holds. Throws InputError when a measured angle lies outside what
// its test produced over the box (the parameters cannot reproduce it) or a test has no angle.
nlohmann::json run_calibration(const CalibrationFile &file, const std::filesystem::path &out, PluginRegistry &registry);

// Simulates every test at one parameter set (the --at check and the round trip); writes <out>/at.json.
nlohmann::json run_at(const CalibrationFile &file, const std::vector<double> &values, const std::filesystem::path &out,
                      PluginRegistry &registry);

}  // namespace spreadmap::calibrate
