// A workflow file: `version: 1`, a `name`, a `scene` (inline or a file relative to the workflow) and
// an ordered list of `stages`. Loading checks YAML syntax and the file's shape; each stage and the
// scene check their own content (validate()).
#pragma once
#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/diagnostics.hpp"

namespace spreadmap {

namespace fs = std::filesystem;

struct StageEntry {
  std::string kind;  // a row of stage_table()
  YAML::Node config;  // its mapping (may be empty)
  Location where;
  // Its settings checked against the stage's schema (stage_table.hpp): every key, numbers in SI,
  // tables as JSON; null where a value was refused. Filled by validate_workflow.
  nlohmann::json settings = nlohmann::json::object();
};

struct Workflow {
  fs::path file;  // as given on the command line
  fs::path dir;   // relative paths in the file resolve against this folder
  std::string name;
  YAML::Node root;
  YAML::Node scene;        // the scene mapping
  std::string scene_file;  // where `scene` came from (the workflow or a referenced file)
  std::vector<StageEntry> stages;

  fs::path resolve(const std::string &relative) const {
    return fs::path(relative).is_absolute() ? fs::path(relative) : dir / relative;
  }
};

// Parses a YAML file; syntax errors become InputError "FILE:LINE:COL: ...".
YAML::Node load_yaml(const fs::path &file);
// Throws InputError listing every problem of the file's shape; a stage is one of `stage_names`
// (the runner passes stage_names() of workflow/stage_table.hpp).
Workflow load_workflow(const fs::path &file, const std::vector<std::string> &stage_names);

}  // namespace spreadmap
