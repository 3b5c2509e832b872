// spreadmap map MODEL [--grid NXxNY] [--rq-max VALUE[,VALUE...]] [--confidence P] [--out DIR]
// spreadmap query MODEL --at U=70mm/s,omega=-5rad/s | --best --rq-max 110um [--confidence P] [--grid NXxNY]
#include <fmt/format.h>

#include <cmath>
#include <iostream>
#include <nlohmann/json.hpp>

#include "analysis/table.hpp"
#include "core/error.hpp"
#include "core/suggest.hpp"
#include "core/units.hpp"
#include "workflow/stage/command_line.hpp"
#include "workflow/stage/commands.hpp"
#include "workflow/map/mapping.hpp"

namespace spreadmap {

std::vector<std::string> split_list(const std::string &text);

namespace {

analysis::ModelFile read_model(const std::string &path) {
  try {
    return analysis::load_model_json(path);
  } catch (const std::exception &e) {
    throw InputError(std::string(e.what()) + " (give a model.json written by spreadmap train)");
  }
}

std::vector<double> roughness_list(const std::string &text) {
  std::vector<double> out;
  for (const auto &item : split_list(text)) {
    try {
      out.push_back(parse_in(item, "m"));
    } catch (const std::exception &e) {
      throw InputError("--rq-max " + item + ": " + e.what() + " (e.g. 110um)");
    }
  }
  return out;
}

void print_optimum(const analysis::Optimum &o, const analysis::ModelFile &file, const MapResult &map) {
  if (!o.found) {
    std::cout << fmt::format("R_q <= {}: no setting in the model's input box reaches it with probability {:.2f}\n",
                             display(o.rq_max, "m"), o.confidence);
    return;
  }
  std::cout << fmt::format("R_q <= {} (confidence {:.2f}): {}\n", display(o.rq_max, "m"), o.confidence,
                           describe_optimum(o, file));
  for (const auto &line : analysis::trust_notes(map.trust)) std::cout << "  " << line << "\n";
}

}  // namespace

int cmd_map(int argc, char **argv) {
  namespace po = boost::program_options;
  po::options_description d("map options");
  std::string model, grid, rq_max, out, confidence;
  cli::Common c;
  d.add_options()("model", po::value(&model)->required(), "model.json written by train")(
      "grid", po::value(&grid), "points per input, e.g. 101x81 (the default)")(
      "rq-max", po::value(&rq_max), "wanted roughness, one or a list: 110um or 90um,110um")(
      "confidence", po::value(&confidence)->default_value("0.9"),
      "the optimum's P(R_q <= target) at least this (0.5: by the predicted mean)")(
      "out", po::value(&out), "folder (default map/ beside the model)")("no-figures", "do not render the PNGs");
  c.add(d);
  po::positional_options_description p;
  p.add("model", 1);
  po::variables_map vm;
  if (!cli::parse(argc, argv, d, p, vm, "map MODEL [--grid NXxNY] [--rq-max VALUE[,VALUE...]] [--out DIR]")) return 0;
  c.apply();
  const auto file = read_model(model);
  MapRequest rq;
  if (!grid.empty()) rq.points = parse_grid_points(grid, mapped_inputs(file));
  rq.rq_max = roughness_list(rq_max);
  rq.confidence = parse_confidence(confidence, "--confidence");
  auto &registry = PluginRegistry::global();
  const auto map = make_process_map(registry, file, rq);
  const fs::path dir = out.empty() ? fs::path(model).parent_path() / "map" : fs::path(out);
  std::unique_ptr<analysis::Table> data;
  const fs::path data_csv = fs::path(model).parent_path() / "data.csv";
  if (fs::exists(data_csv)) data = std::make_unique<analysis::Table>(analysis::Table::read_csv(data_csv.string()));
  write_process_map(map, file, dir, data.get(), !vm.count("no-figures"));
  std::cout << fmt::format("{} grid points -> {}\n", map.grid.x.rows(), (dir / "map.csv").string());
  for (const auto &o : map.optima) print_optimum(o, file, map);
  return 0;
}

int cmd_query(int argc, char **argv) {
  namespace po = boost::program_options;
  po::options_description d("query options");
  std::string model, at, rq_max, grid, confidence;
  cli::Common c;
  d.add_options()("model", po::value(&model)->required(), "model.json written by train")(
      "at", po::value(&at), "a setting, e.g. U=70mm/s,omega=-5rad/s (every input of the model)")(
      "best", "the largest V_s whose R_q is at most --rq-max with probability --confidence")(
      "confidence", po::value(&confidence)->default_value("0.9"),
      "for --best: P(R_q <= target) at least this (0.5: by the predicted mean)")(
      "rq-max", po::value(&rq_max), "wanted roughness for --best, e.g. 110um (a list gives one line each)")(
      "grid", po::value(&grid), "search grid for --best, e.g. 101x81");
  c.add(d);
  po::positional_options_description p;
  p.add("model", 1);
  po::variables_map vm;
  if (!cli::parse(argc, argv, d, p, vm, "query MODEL --at U=70mm/s,omega=-5rad/s | --best --rq-max 110um")) return 0;
  c.apply();
  const auto file = read_model(model);
  auto &registry = PluginRegistry::global();
  if (vm.count("best")) {
    if (rq_max.empty()) throw InputError("--best needs --rq-max, e.g. --rq-max 110um");
    MapRequest rq;
    if (!grid.empty()) rq.points = parse_grid_points(grid, mapped_inputs(file));
    rq.rq_max = roughness_list(rq_max);
    rq.confidence = parse_confidence(confidence, "--confidence");
    const auto map = make_process_map(registry, file, rq);
    for (const auto &o : map.optima) print_optimum(o, file, map);
    return 0;
  }
  if (at.empty()) throw InputError("query: give --at NAME=VALUE,... or --best --rq-max VALUE");
  Eigen::MatrixXd x(1, Eigen::Index(file.inputs.size()));
  x.setConstant(std::nan(""));
  std::vector<std::string> names;
  for (const auto &v : file.inputs) names.push_back(v.name);
  for (const auto &item : split_list(at)) {
    const auto eq = item.find('=');
    if (eq == std::string::npos) throw InputError("--at " + item + ": write NAME=VALUE, e.g. U=70mm/s");
    const std::string name = item.substr(0, eq);
    std::size_t k = names.size();
    for (std::size_t i = 0; i < names.size(); ++i)
      if (iequals(names[i], name)) k = i;
    if (k == names.size()) {
      const auto near = closest(name, names);
      throw InputError("--at: the model has no input '" + name + "'" +
                       (near.empty() ? "" : "; did you mean '" + near + "'?") + " (inputs: " + join(names) + ")");
    }
    try {
      x(0, Eigen::Index(k)) = file.inputs[k].unit.empty() ? parse_quantity(item.substr(eq + 1)).value
                                                          : parse_in(item.substr(eq + 1), file.inputs[k].unit);
    } catch (const std::exception &e) {
      throw InputError("--at " + item + ": " + e.what());
    }
  }
  for (Eigen::Index i = 0; i < x.cols(); ++i)
    if (std::isnan(x(0, i))) throw InputError("--at: no value for input '" + names[std::size_t(i)] + "'");
  for (Eigen::Index i = 0; i < x.cols(); ++i) {
    const auto &v = file.inputs[std::size_t(i)];
    if (x(0, i) < v.min || x(0, i) > v.max)
      spdlog::warn("{} = {} is outside the training range {} .. {}: the prediction extrapolates", v.name,
                   display(x(0, i), v.unit), display(v.min, v.unit), display(v.max, v.unit));
  }
  const auto model_ = load_model(registry, file);
  const auto pred = model_->predict(x);
  for (std::size_t o = 0; o < file.outputs.size(); ++o) {
    const auto &v = file.outputs[o];
    std::cout << fmt::format("{:<10} {}", v.name, display(pred.mean(0, Eigen::Index(o)), v.unit));
    if (pred.std.size() > 0) std::cout << " +- " << display(pred.std(0, Eigen::Index(o)), v.unit);
    std::cout << "\n";
  }
  return 0;
}

}  // namespace spreadmap
