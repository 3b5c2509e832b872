// The one table of spreadmap's commands: the program's own (run, validate, plugins, stages, query,
// render, report) and, generated from stage_table(), each stage's stand-alone command. The usage
// text, the dispatch, the did-you-mean for a mistyped command and `spreadmap stages` read it.
#pragma once
#include <string>
#include <vector>

#include "workflow/stage_table.hpp"

namespace spreadmap::cli {

struct CommandInfo {
  std::string name;
  std::string args;     // what follows the name in the usage line: "WORKFLOW", "[NAME]"
  std::string summary;  // one line
  int (*run)(int argc, char **argv);  // argv from the command's name on; returns the exit status
  std::string alias;                  // another spelling ("characterize"), or ""
  const StageInfo *stage;             // the stage it runs on user files, or null
};

// In the usage's order: run first, then the stages' commands in workflow order, then the rest.
const std::vector<CommandInfo> &command_table();
// The command of that name or alias, or null.
const CommandInfo *find_command(const std::string &name);
std::vector<std::string> command_names();
// `spreadmap --help`.
std::string usage();

// The program: the command named by argv[1], its errors printed and turned into the exit status.
int run_command_line(int argc, char **argv);

}  // namespace spreadmap::cli
