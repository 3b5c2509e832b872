// The spreading scene: a preset (quick | standard | paper | paper_full) overridden key by key by the workflow,
// validated against the host's own schemas and the schemas of the plugins it names, resolved to
// one JSON object in SI. A case of the design is that scene with some keys replaced.
//
// Resolved layout:
//   preset, precision, backend, threads, deterministic, gravity
//   domain   {length, width, height, periodic_x, periodic_y}
//   powder   {diameter, density, count, volume, distribution, basis, d10, d50, d90, sigma,
//             standard_deviation, d_min, d_max, table (SI rows), seed,
//             heap_from, heap_to, heap_top, settle_time, settle_speed,
//             settle_fraction}
//   time     {step, safety, skin, relax, checkpoint_interval, snapshots, overlap_limit}
//   contact  {use, params{...}}                  particle-particle law
//   substrate{law{...}, roughness{rq, correlation_length, sphere_diameter}
//             | height_map{file, digest, sphere_diameter}}
//                                                the same law with the substrate's overrides; roughness
//                                                or height_map only for a substrate of spheres (neither:
//                                                the flat plate)
//   spreader {use, params{...}, law{...}}        geometry and the particle-spreader law
//   layers   {count, thickness}                  spreading layer upon layer (count 1: one pass)
#pragma once
#include <optional>
#include <string>

#include "core/diagnostics.hpp"
#include "core/registry.hpp"
#include "workflow/spreading/scene_key.hpp"
#include "workflow/spreading/scene_model.hpp"
#include "workflow/file/workflow.hpp"

namespace spreadmap {

// Validates and resolves the workflow's scene; problems go to diag. Empty only when the problems
// leave no scene to type (the stages then skip their checks that need one).
std::optional<Scene> resolve_scene(const Workflow &wf, PluginRegistry &registry, Diagnostics &diag);

// Resolves a design variable's name (U, omega, gap, seed, precision, or section.key) against a
// resolved scene; false, with the reason in `why`, when the scene has no such key.
bool find_scene_key(const Scene &scene, PluginRegistry &registry, const std::string &name, SceneKey &out,
                    std::string &why);

const char *preset_text(const std::string &preset);  // the preset's YAML (documentation and tests)

}  // namespace spreadmap
