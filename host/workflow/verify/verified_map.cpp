#include "workflow/verify/verified_map.hpp"

#include "workflow/run/run_dir.hpp"

#include <set>
#include <nlohmann/json.hpp>

#include "analysis/table.hpp"
#include "workflow/figures/stage_figures.hpp"
#include "workflow/map/mapping.hpp"

namespace spreadmap {

void redraw_verified_map(StageContext &ctx, const analysis::ModelFile &model, const nlohmann::json &optimum,
                         int verified) {
  const fs::path dir = ctx.run.map_dir();
  if (!fs::exists(dir / "map.csv")) return;
  const auto grid = analysis::Table::read_csv((dir / "map.csv").string());
  MapRequest rq;
  for (const auto &input : model.inputs) {
    const auto values = grid.numbers(input.name);
    rq.points.push_back(std::set<double>(values.begin(), values.end()).size());
  }
  for (const auto &o : optimum.value("optima", nlohmann::json::array())) rq.rq_max.push_back(o.value("rq_max", 0.0));
  rq.confidence = optimum.value("confidence", 0.5);  // an optimum.json without it was chosen by the mean
  const auto map = make_process_map(ctx.registry, model, rq);
  if (!map.vs || !map.rq) return;
  const fs::path data_csv = ctx.run.train_dir(model.plugin_name()) / "data.csv";
  const analysis::Table cases = fs::exists(data_csv) ? analysis::Table::read_csv(data_csv.string()) : analysis::Table();
  figures::process_map(map.grid, *map.vs, *map.rq, map.frontier, map.optima, dir / "map.png", cases, verified,
                       map.trust);
}

}  // namespace spreadmap
