// Fitting a surrogate to a table of cases and scoring it: the study's Table 4 (train/test) under a
// holdout, cross-validated errors (nrmse_cv and its spread over the folds) always when there are
// rows enough; shared by the train stage and `spreadmap train`. Writes, into one folder: model.json,
// report.json, report.csv, parity.csv (true against predicted per row), data.csv (the rows used,
// with their split), cv.csv (each cross-validated row's out-of-fold prediction and fold) and
// parity.png.
#pragma once
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "analysis/model_file.hpp"
#include "analysis/report.hpp"
#include "analysis/table.hpp"
#include "analysis/validation.hpp"
#include "core/registry.hpp"

namespace spreadmap {

struct TrainRequest {
  std::string model;                                 // surrogate plugin
  nlohmann::json params = nlohmann::json::object();  // validated SI values of its schema
  std::vector<std::string> inputs, outputs;          // column names
  analysis::Validation validation;                   // auto (by size) unless asked
  std::uint64_t seed = 1;                            // of the split and the folds
  std::map<std::string, std::string> units;          // column -> SI unit, for model.json
};

struct TrainResult {
  analysis::ModelFile model;
  analysis::Report report;  // cross-validation: train scores are the all-rows model's, no test rows
  analysis::Table data;     // rows used: inputs, outputs, split
};

TrainResult train_surrogate(PluginRegistry &registry, const analysis::Table &table, const TrainRequest &request,
                            const std::filesystem::path &out_dir, bool figures);

// One output's scores in a line: "NRMSE cv 3.10 +- 1.20 % (9 folds), train 0.52 %; R cv 0.9712;
// noise 1.2 um, signal 4.3 um" (the test scores under a holdout; nulls left out).
std::string score_line(const analysis::Report &report, const analysis::OutputScores &scores);

// Validates the surrogate's parameters given as "key=value" texts (command line). Throws InputError.
nlohmann::json surrogate_params(PluginRegistry &registry, const std::string &model,
                                const std::vector<std::string> &assignments);

// Column units from a metrics.units.json beside the table, when there is one.
std::map<std::string, std::string> units_beside(const std::filesystem::path &table_csv);

}  // namespace spreadmap
