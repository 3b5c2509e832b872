// The one table of workflow stages: each row is a stage's name, what it does, its factory, whether
// it needs the workflow's scene, its settings (checked with the plugins' schema system: units,
// ranges, did-you-mean, file:line) and the stand-alone command that runs it on user files. The
// workflow loader, the runner, `spreadmap stages`, the command line's usage and its did-you-mean
// all read this table; a new stage is one row here and its own folder.
#pragma once
#include <spreadmap/abi.h>

#include <spreadmap/params.hpp>

#include <memory>
#include <string>
#include <vector>

#include "core/schema.hpp"

namespace spreadmap {

class Stage;

struct StageInfo {
  const char *name;
  const char *summary;
  std::unique_ptr<Stage> (*make)();
  bool needs_scene;
  SchemaView settings;
  // "metrics": the stage also takes the parameters of the plugin of that kind named by its `use`
  // setting, which the stage checks against that plugin's schema. nullptr: its settings are all.
  const char *plugin_settings;
  // Its stand-alone command (`spreadmap characterise STATE`), or null: `command_args` is what
  // follows the name in the usage line, `command_summary` what the command does, and `alias`
  // another spelling of it.
  int (*command)(int argc, char **argv);
  const char *command_args;
  const char *command_summary;
  const char *alias;
};

// In the order a workflow runs them.
const std::vector<StageInfo> &stage_table();
// The row of that stage, or null.
const StageInfo *find_stage(const std::string &name);
std::vector<std::string> stage_names();

// The settings of one stage entry, checked against its row: every key of `settings` present (its
// default when not given), numbers in SI, tables as JSON; problems go to `diag`.
nlohmann::json check_stage_settings(const StageInfo &info, const YAML::Node &config, const std::string &file,
                                    Diagnostics &diag);

}  // namespace spreadmap
