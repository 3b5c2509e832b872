// The process map of a trained model: predictions over a grid of the input box (map.csv), the best
// operating point for each wanted roughness (optimum.json) and the frontier of largest V_s per R_q
// (frontier.csv), plus the map and response-surface figures. Shared by the map stage, `spreadmap
// map` and `spreadmap query`.
#pragma once
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "analysis/grid.hpp"
#include "analysis/model_file.hpp"
#include "analysis/optimum.hpp"
#include "analysis/plugin_model.hpp"
#include "core/registry.hpp"

namespace spreadmap {

// The model of a model.json, ready to predict. Its predictions are checked: a NaN or infinite one (a
// damaged state, e.g. a GP length scale of 1e308) throws InputError naming the file, never a number.
std::unique_ptr<analysis::Model> load_model(PluginRegistry &registry, const analysis::ModelFile &file);

struct MapRequest {
  std::vector<std::size_t> points;  // per input; empty = the default (101 x 81)
  std::vector<double> rq_max;       // wanted roughness values [m]
};

struct MapResult {
  analysis::GridMap grid;
  std::optional<std::size_t> vs, rq;  // output columns of V_s and R_q, when the model has them
  std::vector<analysis::Optimum> optima;
  analysis::Table frontier;
};

MapResult make_process_map(PluginRegistry &registry, const analysis::ModelFile &file, const MapRequest &request);
// Writes map.csv, optimum.json, frontier.csv and (figures) map.png, surface_<output>.png into dir;
// `training` (data.csv of the model) adds the simulated cases to the surfaces when given.
void write_process_map(const MapResult &map, const analysis::ModelFile &file, const std::filesystem::path &dir,
                       const analysis::Table *training, bool figures);

// The inputs a map spans: the model's, less a two-fidelity model's fidelity (held at 1).
std::size_t mapped_inputs(const analysis::ModelFile &file);
// "101x81" -> {101, 81}, one count per mapped input (`inputs` of them). Throws InputError.
std::vector<std::size_t> parse_grid_points(const std::string &text, std::size_t inputs);
// Index of an output by name (case-insensitive): vs / rq.
std::optional<std::size_t> output_index(const analysis::ModelFile &file, const std::string &name);
// A value with its SI unit in display form: 3.3e-05 m^2/s -> "33.3 mm^2/s", 1.1e-4 m -> "110 um".
std::string display(double value, const std::string &unit);

}  // namespace spreadmap
