// spreadmap characterise STATE --region X0:X1,Y0:Y1 [--grid CELL] [--U SPEED] [--gap GAP]
//                              [--periodic-y WIDTH] [--heightmap FILE.vti] [--format table|csv|json]
#include <fmt/format.h>

#include <cmath>
#include <iostream>
#include <nlohmann/json.hpp>
#include <yaml-cpp/yaml.h>

#include "core/error.hpp"
#include "core/heightmap_vti.hpp"
#include "core/schema.hpp"
#include "core/units.hpp"
#include "workflow/stage/command_line.hpp"
#include "workflow/stage/commands.hpp"
#include "workflow/stage/plugin_needs.hpp"
#include "workflow/characterise/layer_eval.hpp"
#include "core/units.hpp"

namespace spreadmap {

namespace {
double length_option(const std::string &text, const std::string &what, const std::string &unit = "m") {
  try {
    return parse_in(text, unit);
  } catch (const std::exception &e) {
    throw InputError(what + " " + text + ": " + e.what());
  }
}

std::string cell(const nlohmann::json &v) { return v.is_number() ? fmt::format("{:.10g}", v.get<double>()) : "null"; }
}  // namespace

int cmd_characterise(int argc, char **argv) {
  namespace po = boost::program_options;
  po::options_description d("characterise options");
  std::string state, region, grid, speed, gap, periodic, vti, format = "table", plugin;
  cli::Common c;
  d.add_options()("state", po::value(&state)->required(),
                  "particle file: spreadmap .vtp or CSV with x, y, z, radius [m]")(
      "region", po::value(&region)->required(),
      "sampling rectangle X0:X1,Y0:Y1, lengths with units (bare = m), e.g. 14mm:24mm,0:2.5mm")(
      "grid", po::value(&grid), "height-map cell, e.g. 50um (default: the plugin's, diameter/5)")(
      "U", po::value(&speed), "spreader speed, e.g. 100mm/s (gives V_s)")(
      "gap", po::value(&gap), "spreader gap, e.g. 0.5mm (gives the packing over the gap)")(
      "periodic-y", po::value(&periodic), "width of a periodic strip [0, W] in y: periodic images count")(
      "heightmap", po::value(&vti), "also write the height map as VTK ImageData (.vti)")(
      "metrics", po::value(&plugin), "metrics plugin (default: the first that gives V_s and R_q)")(
      "format", po::value(&format)->default_value("table"), "table | csv | json");
  c.add(d);
  po::positional_options_description p;
  p.add("state", 1);
  po::variables_map vm;
  if (!cli::parse(argc, argv, d, p, vm,
                  "characterise STATE --region X0:X1,Y0:Y1 [--grid CELL] [--U SPEED] [--gap GAP] [--periodic-y WIDTH] "
                  "[--heightmap FILE.vti] [--format table|csv|json]"))
    return 0;
  c.apply();
  if (format != "table" && format != "csv" && format != "json")
    throw InputError("--format " + format + ": use table, csv or json");

  LayerRequest rq;
  rq.plugin = plugin.empty() ? contract_metrics_plugin(PluginRegistry::global(), "spreadmap characterise").descriptor->name
                             : plugin;
  {
    Diagnostics diag;  // the plugin's defaults; --grid overrides its cell
    const LoadedPlugin &p = PluginRegistry::global().get("metrics", rq.plugin);
    rq.params = validate_params(SchemaView::of(*p.descriptor), YAML::Node(), "<defaults>", "--metrics " + rq.plugin, diag);
    diag.throw_if_any();
  }
  rq.region = parse_region(region, "--region");
  if (!grid.empty()) rq.params["grid"] = length_option(grid, "--grid");
  if (!speed.empty()) rq.speed = length_option(speed, "--U", "m/s");
  if (!gap.empty()) rq.gap = length_option(gap, "--gap");
  if (!periodic.empty()) rq.periodic_y = std::make_pair(0.0, length_option(periodic, "--periodic-y"));
  const auto particles = read_particle_file(state);
  const LayerResult r = characterise_layer(PluginRegistry::global(), rq, particles);
  for (const auto &w : r.warnings) spdlog::warn("{}", w);
  if (!vti.empty() && !r.height.empty()) write_heightmap_vti(vti, r.nx, r.ny, r.x0, r.y0, r.cell, r.height.data());

  std::vector<std::string> names;
  for (const auto &m : standard_metric_order())
    if (r.metrics.contains(m)) names.push_back(m);
  for (auto &[k, v] : r.metrics.items())
    if (std::find(names.begin(), names.end(), k) == names.end()) names.push_back(k);

  if (format == "json") {
    std::cout << r.metrics.dump(2) << "\n";
  } else if (format == "csv") {
    for (std::size_t i = 0; i < names.size(); ++i) std::cout << (i ? "," : "") << names[i];
    std::cout << "\n";
    for (std::size_t i = 0; i < names.size(); ++i)
      std::cout << (i ? "," : "") << (r.metrics[names[i]].is_number() ? cell(r.metrics[names[i]]) : "");
    std::cout << "\n";
  } else {
    std::cout << fmt::format("{}: {} particles, region x {:.4g}..{:.4g} mm, y {:.4g}..{:.4g} mm\n", state,
                             particles.size(), rq.region.x0 * 1e3, rq.region.x1 * 1e3, rq.region.y0 * 1e3,
                             rq.region.y1 * 1e3);
    for (const auto &n : names) {
      const auto &v = r.metrics[n];
      const std::string unit = r.units.value(n, "");
      std::cout << fmt::format("  {:<22} {:>16}   {}\n", n,
                               v.is_number() ? fmt::format("{:.6g}", v.get<double>()) : "undefined",
                               v.is_number() ? "(" + display(v.get<double>(), unit) + ")" : "");
    }
  }
  return 0;
}

}  // namespace spreadmap
