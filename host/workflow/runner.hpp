// Running a workflow: load it, validate everything (scene, every stage), then run the selected
// stages in order.
#pragma once
#include <memory>
#include <optional>
#include <vector>

#include "workflow/spreading/scene_model.hpp"
#include "workflow/stage/stage.hpp"

namespace spreadmap {

// validate_workflow loads and checks everything and runs nothing (`spreadmap validate`).
struct Validated {
  Workflow wf;
  std::optional<Scene> scene;
  std::vector<std::unique_ptr<Stage>> stages;
};
Validated validate_workflow(const fs::path &file, PluginRegistry &registry);
int run_workflow(const fs::path &file, const RunOptions &options, PluginRegistry &registry);

}  // namespace spreadmap
