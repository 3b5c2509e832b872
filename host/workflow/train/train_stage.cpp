// train: fits each named surrogate to metrics.csv (inputs: the design's variables; outputs: V_s
// and R_q unless given) and scores it (cross-validated, and as the study's Table 4 under a
// holdout), into train/<model>/. After a multi-layer simulation (metrics.csv has a `layer` column)
// it trains on the last layer's rows: the bed the spreader meets once the layers below settled.
#include <spdlog/spdlog.h>

#include <algorithm>
#include <nlohmann/json.hpp>

#include "analysis/table.hpp"
#include "core/error.hpp"
#include "core/schema.hpp"
#include "core/suggest.hpp"
#include "workflow/stage/stage.hpp"
#include "workflow/run/run_dir.hpp"
#include "workflow/spreading/scene_model.hpp"
#include "workflow/train/train_config.hpp"
#include "workflow/train/training.hpp"

namespace spreadmap {
namespace {

analysis::Table last_layer_rows(const analysis::Table &table) {
  if (!table.has_column("layer")) return table;
  const auto layers = table.numbers("layer");
  const double last = *std::max_element(layers.begin(), layers.end());
  analysis::Table out(table.columns(), table.source() + " (layer " + analysis::Table::format(last) + ")");
  for (std::size_t r = 0; r < table.rows(); ++r)
    if (layers[r] == last) {
      std::vector<std::string> cells;
      for (std::size_t c = 0; c < table.cols(); ++c) cells.push_back(table.text(r, c));
      out.add_row(cells);
    }
  spdlog::info("train: metrics.csv holds {} layers per case; training on the last one ({} rows)",
               analysis::Table::format(last), out.rows());
  return out;
}

class TrainStage : public Stage {
 public:
  void validate(const Workflow &wf, const StageEntry &entry, const Scene *, PluginRegistry &registry,
                Diagnostics &diag) override {
    config_ = read_train_config(wf, entry, registry, diag);
  }

  void run(StageContext &ctx) override {
    figures::use_style(config_.style);
    const fs::path csv = ctx.run.metrics_csv();
    if (!fs::exists(csv))
      throw InputError("train: " + csv.string() + " does not exist; run the characterise stage first");
    const auto table = last_layer_rows(analysis::Table::read_csv(csv.string()));
    std::vector<std::string> inputs = config_.inputs;
    if (inputs.empty())
      for (const auto &v : ctx.run.manifest()["design"].value("variables", nlohmann::json::array()))
        inputs.push_back(v["name"]);
    for (auto &[model, params] : config_.models) {
      TrainRequest rq;
      rq.model = model;
      rq.params = params;
      rq.inputs = inputs;
      rq.outputs = config_.outputs;
      rq.validation = config_.validation;
      rq.seed = config_.seed;
      rq.units = units_beside(csv);
      const auto result = train_surrogate(ctx.registry, table, rq, ctx.run.train_dir(model), config_.render);
      for (const auto &o : result.report.outputs)
        spdlog::info("train {}: {} {}", model, o.name, score_line(result.report, o));
      for (const auto &n : result.report.notes) spdlog::info("train {}: {}", model, n);
    }
  }

 private:
  TrainConfig config_;
};

}  // namespace

std::unique_ptr<Stage> make_train_stage() { return std::make_unique<TrainStage>(); }

}  // namespace spreadmap
