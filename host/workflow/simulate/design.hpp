// The design of simulations: which variants of the scene to run. Types: full_factorial (every
// combination of the listed values, in the order written, last variable fastest), latin_hypercube
// (`samples` points in [min, max] of each variable, seeded), list (explicit cases) and adaptive
// (see the train issue: a few space-filling cases, then the most uncertain one next).
//
// Values carry units as users write them: `U: [40 mm/s, 70 mm/s, 100 mm/s]` or `U: 40, 70, 100 mm/s`
// (one unit for the whole list) or a range `U: {from: 40 mm/s, to: 100 mm/s, step: 15 mm/s}`.
#pragma once
#include "core/yaml_fwd.hpp"

#include <nlohmann/json_fwd.hpp>
#include <string>
#include <vector>

#include "core/diagnostics.hpp"
#include "core/registry.hpp"
#include "workflow/spreading/scene_section.hpp"
#include "analysis/known_columns.hpp"

namespace spreadmap {

struct DesignVariable {
  SceneKey key;
  std::vector<double> values;  // SI; for latin_hypercube the two bounds
};

struct Design {
  std::string type = "full_factorial";
  std::vector<DesignVariable> variables;
  std::vector<std::vector<double>> cases;  // one row per case, values in variable order (SI)
  // adaptive
  std::size_t initial = 9, budget = 0;
  double target_nrmse = 0;  // percent
  std::vector<std::string> outputs = {spread_rate_column, roughness_column};
  // adaptive with two fidelities (`fidelity: {cheap: {KEY: VALUE, ...}, expensive_budget: N}`): the
  // scene keys set on the cheap cases (one value each) and the most expensive cases; `budget` then
  // caps the cheap ones. Empty: one fidelity.
  std::vector<DesignVariable> cheap;
  std::size_t expensive_budget = 0;
};

Design parse_design(const YAML::Node &node, const std::string &file, const std::string &key_path, const Scene &scene,
                    PluginRegistry &registry, Diagnostics &diag);

// Parses a list of quantities in the unit of `param` (see above); records errors in diag.
std::vector<double> parse_value_list(const YAML::Node &node, const sm_param_v1 &param, const std::string &file,
                                     const std::string &key_path, Diagnostics &diag);

// The scene of one case: `scene` with the design variables set (apply_scene_value), and the cheap
// fidelity's keys too when `cheap`.
Scene case_scene(const Scene &scene, const Design &design, std::size_t index, bool cheap = false);
// {name: value} of one case, SI.
nlohmann::json case_inputs(const Design &design, std::size_t index);

}  // namespace spreadmap
