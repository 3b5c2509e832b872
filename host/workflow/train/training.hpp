// Fitting a surrogate to a table of cases and scoring it as the study's Table 4; shared by the
// train stage and `spreadmap train`. Writes, into one folder: model.json, report.json, report.csv,
// parity.csv (true against predicted per row), data.csv (the rows used, with their split) and
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
#include "core/registry.hpp"

namespace spreadmap {

struct TrainRequest {
  std::string model = "bpnn";                        // surrogate plugin
  nlohmann::json params = nlohmann::json::object();  // validated SI values of its schema
  std::vector<std::string> inputs, outputs;          // column names
  std::string split = "study";                       // study | kfold | column
  std::size_t folds = 5;
  std::uint64_t seed = 1;
  std::string split_column = "split";
  std::map<std::string, std::string> units;  // column -> SI unit, for model.json
};

struct TrainResult {
  analysis::ModelFile model;
  analysis::Report report;  // k-fold: test scores are the out-of-fold predictions'
  analysis::Table data;     // rows used: inputs, outputs, split
};

TrainResult train_surrogate(PluginRegistry &registry, const analysis::Table &table, const TrainRequest &request,
                            const std::filesystem::path &out_dir, bool figures);

// Validates the surrogate's parameters given as "key=value" texts (command line). Throws InputError.
nlohmann::json surrogate_params(PluginRegistry &registry, const std::string &model,
                                const std::vector<std::string> &assignments);

// Column units from a metrics.units.json beside the table, when there is one.
std::map<std::string, std::string> units_beside(const std::filesystem::path &table_csv);

}  // namespace spreadmap
