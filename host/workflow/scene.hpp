// The spreading scene: a preset (quick | standard | paper) overridden key by key by the workflow,
// validated against the host's own schemas and the schemas of the plugins it names, resolved to
// one JSON object in SI. A case of the design is that scene with some keys replaced.
//
// Resolved layout:
//   preset, precision, backend, threads, deterministic, gravity
//   domain   {length, width, height, periodic_x, periodic_y}
//   powder   {diameter, density, count, volume, distribution, d50, sigma, table, seed,
//             heap_from, heap_to, heap_top, settle_time, settle_speed}
//   time     {step, safety, skin, relax, checkpoint_interval, snapshots, overlap_limit}
//   contact  {use, params{...}}                  particle-particle law
//   substrate{law{...}}                          the same law with the substrate's overrides
//   spreader {use, params{...}, law{...}}        geometry and the particle-spreader law
#pragma once
#include <nlohmann/json.hpp>
#include <string>

#include "core/diagnostics.hpp"
#include "core/registry.hpp"
#include "workflow/workflow.hpp"

namespace spreadmap {

// Validates and resolves the workflow's scene; problems go to diag.
nlohmann::json resolve_scene(const Workflow &wf, PluginRegistry &registry, Diagnostics &diag);

// A design variable: the short name users write (U, omega, gap, seed) or a dotted path
// (contact.friction, powder.count, spreader.diameter), and where it lives in the resolved scene.
struct SceneKey {
  std::string name;                  // as written
  nlohmann::json::json_pointer path; // into the resolved scene
  const sm_param_v1 *param = nullptr;// schema entry (units, range)
};
// Resolves a variable name against a resolved scene; records an error when unknown.
bool find_scene_key(const nlohmann::json &scene, PluginRegistry &registry, const std::string &name, SceneKey &out,
                    std::string &why);

const char *preset_text(const std::string &preset);  // the preset's YAML (documentation and tests)

}  // namespace spreadmap
