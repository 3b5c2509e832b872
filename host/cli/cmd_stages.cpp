// `spreadmap stages [NAME]`: the workflow stages (stage_table.hpp) and, for one, its settings, printed
// as `spreadmap plugins NAME` prints a plugin's parameters.
#include <boost/program_options.hpp>
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>

#include "cli/command_table.hpp"
#include "cli/program_commands.hpp"
#include "core/error.hpp"
#include "core/schema.hpp"
#include "core/suggest.hpp"
#include "workflow/stage/command_line.hpp"

namespace spreadmap::cli {
namespace {

std::string command_of(const StageInfo &s) {
  return s.command ? std::string("spreadmap ") + s.name + " " + s.command_args : std::string();
}

std::string describe_stage(const StageInfo &s) {
  std::string out = std::string("stage ") + s.name + " — " + s.summary + "\n";
  out += std::string("  needs the workflow's scene: ") + (s.needs_scene ? "yes" : "no") + "\n";
  if (s.command) out += "  stand-alone: " + command_of(s) + " (" + s.command_summary + ")\n";
  out += describe_params(s.settings, "setting");
  if (s.plugin_settings)
    out += std::string("  and the parameters of the ") + s.plugin_settings +
           " plugin named by `use` (spreadmap plugins --kind " + s.plugin_settings + ")\n";
  return out;
}

nlohmann::json stage_json(const StageInfo &s) {
  return {{"name", s.name},
          {"summary", s.summary},
          {"needs_scene", s.needs_scene},
          {"command", command_of(s)},
          {"plugin_settings", s.plugin_settings ? s.plugin_settings : ""},
          {"settings", params_json(s.settings)}};
}

}  // namespace

int cmd_stages(int argc, char **argv) {
  namespace po = boost::program_options;
  po::options_description d("stages options");
  std::string name, format = "table";
  Common c;
  d.add_options()("name", po::value(&name), "one stage: print its settings")(
      "format", po::value(&format)->default_value("table"), "table | json");
  c.add(d);
  po::positional_options_description p;
  p.add("name", 1);
  po::variables_map vm;
  if (!parse(argc, argv, d, p, vm, "stages [NAME] [--format table|json]")) return 0;
  c.apply();
  if (format != "table" && format != "json")
    throw InputError("--format " + format + ": write table or json");
  if (!name.empty() && !find_stage(name)) {
    const std::string near = closest(name, stage_names());
    throw InputError("no stage named '" + name + "'" + (near.empty() ? "" : "; did you mean '" + near + "'?") +
                     " stages: " + join(stage_names()));
  }
  nlohmann::json all = nlohmann::json::array();
  for (const auto &s : stage_table()) {
    if (!name.empty() && name != s.name) continue;
    if (format == "json") all.push_back(stage_json(s));
    else if (name.empty()) std::printf("%-13s %s\n", s.name, s.summary);
    else std::cout << describe_stage(s);
  }
  if (format == "json") std::cout << all.dump(2) << "\n";
  return 0;
}

}  // namespace spreadmap::cli
