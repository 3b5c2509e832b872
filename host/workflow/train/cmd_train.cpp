// spreadmap train TABLE.csv --inputs U,omega --outputs vs,rq --model bpnn|gp [--out DIR]
//                [--split auto|holdout|kfold:K|loo|column:NAME] [--split-column NAME] [--folds K] [--seed N]
//                [--param KEY=VALUE ...] [--format table|json]
#include <fmt/format.h>

#include <cmath>
#include <iostream>
#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "workflow/stage/command_line.hpp"
#include "workflow/stage/commands.hpp"
#include "workflow/stage/plugin_needs.hpp"
#include "core/units.hpp"
#include "workflow/train/train_config.hpp"
#include "workflow/train/training.hpp"

namespace spreadmap {

std::vector<std::string> split_list(const std::string &text) {
  std::vector<std::string> out;
  std::size_t pos = 0;
  while (pos <= text.size()) {
    const auto comma = text.find(',', pos);
    const std::string item = text.substr(pos, comma == std::string::npos ? std::string::npos : comma - pos);
    if (!item.empty()) out.push_back(item);
    if (comma == std::string::npos) break;
    pos = comma + 1;
  }
  return out;
}

namespace {

// The scores as one JSON document (--format json), the outputs by name.
void print_scores_json(const analysis::Report &report, const std::string &model, const fs::path &dir) {
  nlohmann::json j = nlohmann::json::object();
  const nlohmann::json scores = report.to_json();
  for (const auto &o : scores["outputs"]) j[o["name"].get<std::string>()] = o;
  std::cout << nlohmann::json({{"model", "surrogate/" + model},
                               {"split", report.split},
                               {"split_reason", report.split_reason},
                               {"n_train", report.n_train},
                               {"n_test", report.n_test},
                               {"cv_rows", report.cv_rows},
                               {"cv_folds", report.cv_folds},
                               {"outputs", j},
                               {"notes", report.notes},
                               {"model_file", (dir / "model.json").string()}})
                   .dump(2)
            << "\n";
}

// The scores as a table (--format table), with the fitted noise and signal scales and the notes.
void print_scores_table(const analysis::Report &report, const std::string &model, const std::string &table,
                        const fs::path &dir) {
  std::cout << fmt::format("surrogate/{} on {} ({} train, {} test rows; split {}: {}): {}\n", model, table,
                           report.n_train, report.n_test, report.split, report.split_reason,
                           (dir / "model.json").string());
  const auto cell = [](double v, int digits) { return std::isfinite(v) ? fmt::format("{:.{}f}", v, digits) : "-"; };
  std::cout << fmt::format("  {:<12} {:>14} {:>14} {:>16} {:>8} {:>8} {:>8}\n", "output", "NRMSE train %",
                           "NRMSE test %", "NRMSE cv %", "R train", "R test", "R cv");
  for (const auto &o : report.outputs) {
    const std::string cv = std::isfinite(o.nrmse_cv) ? cell(o.nrmse_cv, 3) + " +- " + cell(o.nrmse_cv_sd, 3) : "-";
    std::cout << fmt::format("  {:<12} {:>14} {:>14} {:>16} {:>8} {:>8} {:>8}\n", o.name, cell(o.nrmse_train, 3),
                             cell(o.nrmse_test, 3), cv, cell(o.r_train, 4), cell(o.r_test, 4), cell(o.r_cv, 4));
  }
  for (const auto &o : report.outputs)
    if (std::isfinite(o.noise_std))
      std::cout << fmt::format("  {}: noise {}, signal {} (fitted)\n", o.name, display(o.noise_std, o.unit),
                               display(o.signal_std, o.unit));
  if (report.cv_folds)
    std::cout << fmt::format("  NRMSE cv: {} folds of {} rows, +- the standard deviation over the folds\n",
                             report.cv_folds, report.cv_rows);
  for (const auto &n : report.notes) std::cout << "  note: " << n << "\n";
}

// The table, its inputs and outputs each a column of it.
analysis::Table read_training_table(const std::string &table, const TrainRequest &rq) {
  const auto t = [&] {
    try {
      return analysis::Table::read_csv(table);
    } catch (const std::exception &e) {
      throw InputError(std::string(e.what()));
    }
  }();
  for (const auto &name : rq.inputs)
    if (!t.has_column(name)) throw InputError("--inputs: " + table + " has no column '" + name + "'");
  for (const auto &name : rq.outputs)
    if (!t.has_column(name)) throw InputError("--outputs: " + table + " has no column '" + name + "'");
  return t;
}

}  // namespace

int cmd_train(int argc, char **argv) {
  namespace po = boost::program_options;
  po::options_description d("train options");
  std::string table, inputs, outputs = "vs,rq", out, format = "table", split = "auto", split_column;
  // The train stage's schema holds the defaults of both its settings and these options.
  const SchemaView stage_schema = train_settings();
  const auto stage_default = [&](const char *key) { return std::to_string(long(stage_schema.find(key)->def)); };
  std::size_t folds = 0;
  std::vector<std::string> params;
  TrainRequest rq;
  cli::Common c;
  d.add_options()("table", po::value(&table)->required(), "CSV with a header row")(
      "inputs", po::value(&inputs)->required(), "input columns, comma-separated, e.g. U,omega")(
      "outputs", po::value(&outputs)->default_value(contract_columns()), "output columns, comma-separated")(
      "model", po::value(&rq.model), "surrogate plugin (default: the first installed, in name order)")(
      "out", po::value(&out), "folder for model.json and the report (default train_<model> beside the table)")(
      "split", po::value(&split)->default_value("auto"),
      "auto (by size: holdout from 40 rows, kfold:5 from 12, loo below) | holdout (the study's 35/10) | kfold:K | "
      "loo | column:NAME")("split-column", po::value(&split_column),
                           "a column of train/test labels (= --split column:NAME)")(
      "folds", cli::whole_number("folds", &folds, "a number of folds (2 or more)")->default_value(stage_default("folds")),
      "K of a plain --split kfold")(
      "seed", cli::whole_number("seed", &rq.seed, "a seed (a whole number, 0 or more)")->default_value(stage_default("seed")),
      "seed of the split")("param", po::value(&params)->multitoken(),
                           "surrogate parameter KEY=VALUE (see spreadmap plugins MODEL)")(
      "no-figures", "do not render parity.png")("format", po::value(&format)->default_value("table"), "table | json");
  c.add(d);
  po::positional_options_description p;
  p.add("table", 1);
  po::variables_map vm;
  if (!cli::parse(argc, argv, d, p, vm,
                  "train TABLE.csv --inputs U,omega [--outputs vs,rq] [--model NAME] [--out DIR] [--split "
                  "auto|holdout|kfold:K|loo|column:NAME] "
                  "[--split-column NAME] [--param KEY=VALUE ...] [--format table|json]"))
    return 0;
  c.apply();
  if (format != "table" && format != "json") throw InputError("--format " + format + ": use table or json");
  if (!split_column.empty()) split = "column:" + split_column;
  try {
    rq.validation = analysis::parse_validation(split, folds);
  } catch (const std::exception &e) {
    throw InputError(std::string("--split ") + e.what());
  }
  rq.inputs = split_list(inputs);
  rq.outputs = split_list(outputs);
  auto &registry = PluginRegistry::global();
  if (rq.model.empty()) rq.model = first_surrogate(registry, "spreadmap train");
  rq.params = surrogate_params(registry, rq.model, params);
  rq.units = units_beside(table);
  const analysis::Table t = read_training_table(table, rq);
  const fs::path dir = out.empty() ? fs::path(table).parent_path() / ("train_" + rq.model) : fs::path(out);
  const auto result = train_surrogate(registry, t, rq, dir, !vm.count("no-figures"));
  if (format == "json") print_scores_json(result.report, rq.model, dir);
  else print_scores_table(result.report, rq.model, table, dir);
  return 0;
}

}  // namespace spreadmap
