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
#include "analysis/map_trust.hpp"
#include "analysis/model_file.hpp"
#include "analysis/optimum.hpp"
#include "analysis/plugin_model.hpp"
#include "core/registry.hpp"

namespace spreadmap {

// The model of a model.json, ready to predict. Its predictions are checked: a NaN or infinite one (a
// damaged state, e.g. a GP length scale of 1e308) throws InputError naming the file, never a number.
std::unique_ptr<analysis::Model> load_model(PluginRegistry &registry, const analysis::ModelFile &file);

// The optimum's default confidence: P(R_q <= target) of the chosen setting at least 0.9.
constexpr double default_confidence = 0.9;

struct MapRequest {
  std::vector<std::size_t> points;  // per input; empty = the default (101 x 81)
  std::vector<double> rq_max;       // wanted roughness values [m]
  double confidence = default_confidence;
};

struct MapResult {
  analysis::GridMap grid;
  std::optional<std::size_t> vs, rq;  // output columns of V_s and R_q, when the model has them
  std::vector<analysis::Optimum> optima;
  analysis::Table frontier;
  std::vector<analysis::MapTrust> trust;  // one per output of the model
  double confidence = default_confidence;  // the optimum rule's
  // The outputs an optimum rests on (V_s chooses it, R_q bounds it) whose map is not trusted.
  std::vector<std::string> untrusted_basis() const;
};

// Throws InputError when the request's confidence is above 0.5 and the model has no predictive spread
// of R_q: neither its own std nor a cross-validated RMSE recorded by the train stage.
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
// "U = 70 mm/s, omega = 0 rad/s: V_s = 33.1 mm^2/s, R_q = 104 um +- 2.1 um, P(R_q <= 110 um) = 0.93"
std::string describe_optimum(const analysis::Optimum &optimum, const analysis::ModelFile &file);
// A map confidence from text or YAML ("0.9", "90 %"); throws InputError naming `where` outside [0.5, 1).
double parse_confidence(const std::string &text, const std::string &where);

}  // namespace spreadmap
