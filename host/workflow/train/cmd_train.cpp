// spreadmap train TABLE.csv --inputs U,omega --outputs vs,rq --model bpnn|gp [--out DIR]
//                [--split study|kfold|column] [--split-column NAME] [--folds K] [--seed N]
//                [--param KEY=VALUE ...] [--format table|json]
#include <fmt/format.h>

#include <iostream>

#include "core/error.hpp"
#include "workflow/command_line.hpp"
#include "workflow/commands.hpp"
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

int cmd_train(int argc, char **argv) {
  namespace po = boost::program_options;
  po::options_description d("train options");
  std::string table, inputs, outputs = "vs,rq", out, format = "table", split_column;
  std::vector<std::string> params;
  TrainRequest rq;
  cli::Common c;
  d.add_options()("table", po::value(&table)->required(), "CSV with a header row")(
      "inputs", po::value(&inputs)->required(), "input columns, comma-separated, e.g. U,omega")(
      "outputs", po::value(&outputs)->default_value("vs,rq"), "output columns, comma-separated")(
      "model", po::value(&rq.model)->default_value("bpnn"), "surrogate plugin: bpnn | gp | ...")(
      "out", po::value(&out), "folder for model.json and the report (default train_<model> beside the table)")(
      "split", po::value(&rq.split)->default_value("study"), "study (35/10 share) | kfold | column")(
      "split-column", po::value(&split_column), "a column of train/test labels (implies --split column)")(
      "folds", po::value(&rq.folds)->default_value(5), "folds for --split kfold")(
      "seed", po::value(&rq.seed)->default_value(1), "seed of the split")(
      "param", po::value(&params)->multitoken(), "surrogate parameter KEY=VALUE (see spreadmap plugins MODEL)")(
      "no-figures", "do not render parity.png")("format", po::value(&format)->default_value("table"), "table | json");
  c.add(d);
  po::positional_options_description p;
  p.add("table", 1);
  po::variables_map vm;
  if (!cli::parse(argc, argv, d, p, vm,
                  "train TABLE.csv --inputs U,omega [--outputs vs,rq] [--model bpnn|gp] [--out DIR] [--split "
                  "study|kfold|column] "
                  "[--split-column NAME] [--param KEY=VALUE ...] [--format table|json]"))
    return 0;
  c.apply();
  if (format != "table" && format != "json") throw InputError("error: --format " + format + ": use table or json");
  if (!split_column.empty()) {
    rq.split = "column";
    rq.split_column = split_column;
  }
  rq.inputs = split_list(inputs);
  rq.outputs = split_list(outputs);
  auto &registry = PluginRegistry::global();
  rq.params = surrogate_params(registry, rq.model, params);
  rq.units = units_beside(table);
  const auto t = [&] {
    try {
      return analysis::Table::read_csv(table);
    } catch (const std::exception &e) {
      throw InputError(std::string("error: ") + e.what());
    }
  }();
  for (const auto &name : rq.inputs)
    if (!t.has_column(name)) throw InputError("error: --inputs: " + table + " has no column '" + name + "'");
  for (const auto &name : rq.outputs)
    if (!t.has_column(name)) throw InputError("error: --outputs: " + table + " has no column '" + name + "'");
  const fs::path dir = out.empty() ? fs::path(table).parent_path() / ("train_" + rq.model) : fs::path(out);
  const auto result = train_surrogate(registry, t, rq, dir, !vm.count("no-figures"));

  if (format == "json") {
    nlohmann::json j = nlohmann::json::object();
    for (const auto &o : result.report.outputs)
      j[o.name] = {
          {"nrmse_train", o.nrmse_train}, {"nrmse_test", o.nrmse_test}, {"r_train", o.r_train}, {"r_test", o.r_test}};
    std::cout << nlohmann::json({{"model", "surrogate/" + rq.model},
                                 {"n_train", result.report.n_train},
                                 {"n_test", result.report.n_test},
                                 {"outputs", j},
                                 {"model_file", (dir / "model.json").string()}})
                     .dump(2)
              << "\n";
  } else {
    std::cout << fmt::format("surrogate/{} on {} ({} train, {} test rows, split {}): {}\n", rq.model, table,
                             result.report.n_train, result.report.n_test, rq.split, (dir / "model.json").string());
    std::cout << fmt::format("  {:<12} {:>14} {:>14} {:>10} {:>10}\n", "output", "NRMSE train %", "NRMSE test %",
                             "R train", "R test");
    for (const auto &o : result.report.outputs)
      std::cout << fmt::format("  {:<12} {:>14.3f} {:>14.3f} {:>10.4f} {:>10.4f}\n", o.name, o.nrmse_train,
                               o.nrmse_test, o.r_train, o.r_test);
  }
  return 0;
}

}  // namespace spreadmap
