#include "cli/command_table.hpp"

#include <fmt/format.h>

#include "cli/program_commands.hpp"
#include "workflow/stage/commands.hpp"

namespace spreadmap::cli {

const std::vector<CommandInfo> &command_table() {
  static const std::vector<CommandInfo> table = [] {
    std::vector<CommandInfo> t = {
        {"run", "WORKFLOW", "run a workflow (simulate -> characterise -> train -> map)", cmd_run, "", nullptr}};
    for (const auto &s : stage_table())
      if (s.command) t.push_back({s.name, s.command_args, s.command_summary, s.command, s.alias ? s.alias : "", &s});
    const std::vector<CommandInfo> rest = {
        {"validate", "FILE", "check a workflow, scene or calibration file completely without running anything",
         cmd_validate, "", nullptr},
        {"plugins", "[NAME]", "list plugins and their parameters (the reference manual)", cmd_plugins, "", nullptr},
        {"stages", "[NAME]", "list the workflow stages and their settings", cmd_stages, "", nullptr},
        {"query", "MODEL", "predictions or the best operating point of a trained model", cmd_query, "", nullptr},
        {"render", "STATE", "snapshot of a particle state as PNG", cmd_render, "", nullptr},
        {"report", "RUN_DIR", "rebuild RUN_DIR/report.html, the run's answer on one page", cmd_report, "", nullptr},
    };
    t.insert(t.end(), rest.begin(), rest.end());
    return t;
  }();
  return table;
}

const CommandInfo *find_command(const std::string &name) {
  for (const auto &c : command_table())
    if (name == c.name || (!c.alias.empty() && name == c.alias)) return &c;
  return nullptr;
}

std::vector<std::string> command_names() {
  std::vector<std::string> out;
  for (const auto &c : command_table()) out.push_back(c.name);
  return out;
}

std::string usage() {
  std::string out = "usage: spreadmap <command> [options]\n\ncommands:\n";
  for (const auto &c : command_table()) out += fmt::format("  {:<18}  {}\n", c.name + " " + c.args, c.summary);
  return out + "\n  spreadmap <command> --help    options of a command\n  spreadmap --version\n";
}

}  // namespace spreadmap::cli
