// The train stage's settings, read and checked from the workflow file. The map stage reads them
// too, to know which models the workflow trains.
#pragma once
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "core/diagnostics.hpp"
#include "analysis/validation.hpp"
#include "core/registry.hpp"
#include "core/schema.hpp"
#include "workflow/figures/figure_style.hpp"
#include "workflow/file/workflow.hpp"
#include "analysis/known_columns.hpp"

namespace spreadmap {

struct TrainConfig {
  std::vector<std::pair<std::string, nlohmann::json>> models;  // name, validated parameters
  std::vector<std::string> inputs;                             // empty = the design's variables
  std::vector<std::string> outputs = {spread_rate_column, roughness_column};
  analysis::Validation validation;  // split: auto unless given
  std::size_t folds = 0;            // K of a plain `split: kfold` (the schema gives the default)
  std::uint64_t seed = 0;
  bool render = true;
  figures::Style style;  // render: true | false | {width, vector}
};

// The stage's settings schema (also the defaults of `spreadmap train`'s --folds and --seed).
SchemaView train_settings();

// model: bpnn | [bpnn, gp]; params: {...} (one model) or params: {bpnn: {...}, gp: {...}};
// inputs, outputs: lists of column names; split: auto | holdout | kfold:K | loo | column:NAME (see
// analysis/validation.hpp); folds (K of a plain `kfold`); seed; render.
TrainConfig read_train_config(const Workflow &wf, const StageEntry &entry, PluginRegistry &registry, Diagnostics &diag);

}  // namespace spreadmap
