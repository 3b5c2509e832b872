#include "workflow/simulate/design.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <random>
#include <set>

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <yaml-cpp/yaml.h>

#include "analysis/adaptive.hpp"
#include "analysis/multifidelity.hpp"
#include "core/schema.hpp"
#include "core/suggest.hpp"
#include "core/units.hpp"

namespace spreadmap {

namespace {

// One listed value (`text`, the item of a sequence `n`) in the unit of `param`; an invalid one is
// reported at n's position.
void append_listed_value(const YAML::Node &n, const std::string &text, const sm_param_v1 &param,
                         const std::string &file, const std::string &key_path, Diagnostics &diag,
                         std::vector<double> &out) {
  YAML::Node scalar(text);
  scalar.SetStyle(YAML::EmitterStyle::Default);
  Diagnostics local;
  auto v = validate_value(param, scalar, file, key_path, local);
  if (!local.empty() || !v.is_number()) {
    // re-report with the right position
    validate_value(param, n, file, key_path, diag);
    return;
  }
  out.push_back(v.get<double>());
}

// `{from: A, to: B, step: S}`: A, A + S, ... up to B (within a billionth of the step).
void append_value_range(const YAML::Node &node, const sm_param_v1 &param, const std::string &file,
                        const std::string &key_path, Diagnostics &diag, std::vector<double> &out) {
  auto a = validate_value(param, node["from"], file, key_path + ".from", diag);
  auto b = validate_value(param, node["to"], file, key_path + ".to", diag);
  const sm_param_v1 step_param = {param.name, SM_NUMBER, param.unit, 0, 1e300, 0, nullptr, 0, nullptr, param.doc};
  auto s = validate_value(step_param, node["step"], file, key_path + ".step", diag);
  if (a.is_number() && b.is_number() && s.is_number()) {
    const double from = a, to = b, step = s;
    if (step <= 0) diag.error(Location::of(file, node["step"]), key_path + ".step", "must be positive");
    else
      for (int i = 0; from + i * step <= to + 1e-9 * std::abs(step); ++i) out.push_back(from + i * step);
  }
}

// The unit after the last item's number ("" when it has none, or is no number).
std::string unit_after_number(const std::string &last) {
  std::size_t used = 0;
  try {
    std::stod(last, &used);
    return last.substr(used);
  } catch (...) {
  }
  return "";
}

// "40, 70, 100 mm/s": one unit for the whole list, given after the last value.
void append_comma_list(const YAML::Node &node, const sm_param_v1 &param, const std::string &file,
                       const std::string &key_path, Diagnostics &diag, std::vector<double> &out) {
  std::vector<std::string> parts = split(node.Scalar(), ',');
  const std::string unit = unit_after_number(parts.back());
  for (auto &p : parts) {
    std::size_t used = 0;
    bool bare = false;
    try {
      std::stod(p, &used);
      bare = p.substr(used).find_first_not_of(" \t") == std::string::npos;
    } catch (...) {
    }
    if (bare && !unit.empty()) p += " " + unit.substr(unit.find_first_not_of(" \t"));
    Diagnostics local;
    auto v = validate_value(param, YAML::Node(p), file, key_path, local);
    if (!local.empty()) {
      for (auto e : local.errors()) {
        // attach the node's position
        const std::string tag = file + ": ";
        if (e.rfind(tag, 0) == 0) e = Location::of(file, node).str() + ": " + e.substr(tag.size());
        diag.error(e);
      }
    } else {
      out.push_back(v.get<double>());
    }
  }
}

}  // namespace

std::vector<double> parse_value_list(const YAML::Node &node, const sm_param_v1 &param, const std::string &file,
                                     const std::string &key_path, Diagnostics &diag) {
  std::vector<double> out;
  if (node.IsSequence()) {
    for (const auto &n : node) {
      if (!n.IsScalar()) {
        diag.error(Location::of(file, n), key_path, "expected a value such as 70 mm/s");
        continue;
      }
      append_listed_value(n, n.Scalar(), param, file, key_path, diag, out);
    }
  } else if (node.IsMap() && node["from"] && node["to"] && node["step"]) {
    append_value_range(node, param, file, key_path, diag, out);
  } else if (node.IsScalar()) {
    append_comma_list(node, param, file, key_path, diag, out);
  } else {
    diag.error(Location::of(file, node), key_path, "expected a list of values, e.g. [40 mm/s, 70 mm/s] or 40, 70 mm/s");
  }
  return out;
}

namespace {

// `fidelity: {cheap: {KEY: VALUE, ...}, expensive_budget: N}` of an adaptive design: each cheap key a
// numeric scene key that is not a design variable, with one value.
void parse_fidelity(const YAML::Node &node, const std::string &file, const std::string &key_path, const Scene &scene,
                    PluginRegistry &registry, Design &d, Diagnostics &diag) {
  const std::string example = "{cheap: {domain.width: 1 mm, powder.count: 3357}, expensive_budget: 15}";
  if (!node.IsMap()) return diag.error(Location::of(file, node), key_path, "expected a mapping: " + example);
  static const std::vector<std::string> keys = {"cheap", "expensive_budget"};
  for (const auto &kv : node) {
    const std::string name = kv.first.as<std::string>();
    if (std::find(keys.begin(), keys.end(), name) != keys.end()) continue;
    const std::string near = closest(name, keys);
    diag.error(Location::of(file, kv.first), key_path + "." + name, "unknown key",
               (near.empty() ? "" : "did you mean '" + near + "'? ") + "known: " + join(keys));
  }
  const YAML::Node cheap = node["cheap"];
  if (!cheap || !cheap.IsMap() || cheap.size() == 0)
    return diag.error(Location::of(file, cheap ? cheap : node), key_path + ".cheap",
                      "the scene keys that make a case cheap, each with one value: " + example);
  for (const auto &kv : cheap) {
    const std::string name = kv.first.as<std::string>(), path = key_path + ".cheap." + name;
    DesignVariable var;
    std::string why;
    if (!find_scene_key(scene, registry, name, var.key, why)) {
      diag.error(Location::of(file, kv.first), path, why);
      continue;
    }
    if (var.key.param->type != SM_NUMBER && var.key.param->type != SM_INTEGER) {
      diag.error(Location::of(file, kv.first), path, "only numeric scene keys can set the cheap fidelity");
      continue;
    }
    for (const auto &v : d.variables)
      if (v.key.name == var.key.name)
        diag.error(Location::of(file, kv.first), path, "is a design variable",
                   "the cheap fidelity sets keys the design does not vary");
    const auto value = validate_value(*var.key.param, kv.second, file, path, diag);
    if (!value.is_number()) continue;
    var.values = {value.get<double>()};
    d.cheap.push_back(var);
  }
  d.expensive_budget =
      read_whole_number(node["expensive_budget"], file, key_path + ".expensive_budget", 3, 100000, 15, diag);
  if (d.cases.empty() || d.variables.empty()) return;
  // The starts analysis::multi_fidelity_design takes (adaptive_run.cpp): the budgets must hold them.
  Eigen::MatrixXd candidates(Eigen::Index(d.cases.size()), Eigen::Index(d.variables.size()));
  for (std::size_t i = 0; i < d.cases.size(); ++i)
    for (std::size_t k = 0; k < d.variables.size(); ++k) candidates(Eigen::Index(i), Eigen::Index(k)) = d.cases[i][k];
  const auto lattice = analysis::space_filling_start(candidates);
  const std::size_t expensive_start = analysis::corners_and_centre(candidates, lattice).size();
  const YAML::Node budget_node = node["expensive_budget"] ? node["expensive_budget"] : node;
  if (expensive_start < 3)
    diag.error(Location::of(file, node), key_path,
               fmt::format("the expensive cases start at the corners and centre of the design's box: {} here, "
                           "fewer than the 3 a fit needs",
                           expensive_start),
               "give a variable 3 or more values");
  else if (d.expensive_budget < expensive_start)
    diag.error(Location::of(file, budget_node), key_path + ".expensive_budget",
               fmt::format("{} is below the {} expensive cases the design starts with (the corners and centre of "
                           "its box)",
                           d.expensive_budget, expensive_start),
               fmt::format("give expensive_budget >= {}", expensive_start));
  const std::size_t cheap_start = std::min(lattice.size(), std::max<std::size_t>(2, d.initial));
  if (d.budget < cheap_start)
    diag.error(Location::of(file, node), key_path.substr(0, key_path.rfind('.')) + ".budget",
               fmt::format("{} is below the {} cheap cases the design starts with", d.budget, cheap_start),
               fmt::format("give budget >= {} (or a smaller initial)", cheap_start));
}

// The design types, in the order of design_types (the spelling users write).
enum class DesignType { full_factorial, latin_hypercube, list, adaptive };
const std::vector<std::string> design_types = {"full_factorial", "latin_hypercube", "list", "adaptive"};

// The type the design names (full_factorial when it names none); an unknown one is reported, with
// the nearest known, and gives nullopt. d.type keeps the spelling as written.
std::optional<DesignType> read_design_type(const YAML::Node &node, const std::string &file, const std::string &key_path,
                                           Design &d, Diagnostics &diag) {
  const std::vector<std::string> &types = design_types;
  if (node["type"]) {
    d.type = node["type"].as<std::string>();
    if (std::find(types.begin(), types.end(), d.type) == types.end()) {
      const std::string near = closest(d.type, types);
      diag.error(Location::of(file, node["type"]), key_path + ".type", "unknown design type '" + d.type + "'",
                 (near.empty() ? "" : "did you mean '" + near + "'? ") + "types: " + join(types));
      return std::nullopt;
    }
  }
  return DesignType(std::find(types.begin(), types.end(), d.type) - types.begin());
}

// A whole number setting of the design (samples, seed, initial, budget) in [lo, hi], def when not given.
std::size_t read_design_integer(const YAML::Node &node, const char *key, const std::string &file,
                                const std::string &key_path, std::size_t def, std::size_t lo, std::size_t hi,
                                Diagnostics &diag) {
  return read_whole_number(node[key], file, key_path + "." + key, lo, hi, def, diag);
}

// The design's variables: each key that is not a setting of the design, a numeric scene key with its
// list of values.
void read_design_variables(const YAML::Node &node, const std::string &file, const std::string &key_path,
                           const Scene &scene, PluginRegistry &registry, Design &d, Diagnostics &diag) {
  static const std::set<std::string> reserved = {"type",   "samples",      "seed",    "cases",   "initial",
                                                 "budget", "target_nrmse", "outputs", "fidelity"};
  for (const auto &kv : node) {
    const std::string name = kv.first.as<std::string>();
    if (reserved.count(name)) continue;
    DesignVariable var;
    std::string why;
    if (!find_scene_key(scene, registry, name, var.key, why)) {
      diag.error(Location::of(file, kv.first), key_path + "." + name, why);
      continue;
    }
    if (var.key.param->type != SM_NUMBER && var.key.param->type != SM_INTEGER) {
      diag.error(Location::of(file, kv.first), key_path + "." + name,
                 "only numeric scene keys can be design variables");
      continue;
    }
    var.values = parse_value_list(kv.second, *var.key.param, file, key_path + "." + name, diag);
    if (var.values.empty()) diag.error(Location::of(file, kv.second), key_path + "." + name, "no values given");
    d.variables.push_back(var);
  }
}

// Every combination of the variables' values, in the order written, the last variable fastest.
void add_full_factorial_cases(Design &d) {
  const std::size_t nv = d.variables.size();
  std::size_t total = 1;
  for (const auto &v : d.variables) total *= std::max<std::size_t>(1, v.values.size());
  for (std::size_t c = 0; c < total && nv > 0; ++c) {
    std::vector<double> row(nv);
    std::size_t rest = c;
    for (std::size_t k = nv; k-- > 0;) {
      const auto &vals = d.variables[k].values;
      if (vals.empty()) break;
      row[k] = vals[rest % vals.size()];
      rest /= vals.size();
    }
    d.cases.push_back(row);
  }
}

// An adaptive design's settings: its start, its budget, its target and its cheap fidelity.
void read_adaptive_settings(const YAML::Node &node, const std::string &file, const std::string &key_path,
                            const Scene &scene, PluginRegistry &registry, Design &d, Diagnostics &diag) {
  d.initial =
      read_design_integer(node, "initial", file, key_path, std::min<std::size_t>(9, d.cases.size()), 2, 100000, diag);
  d.budget = read_design_integer(node, "budget", file, key_path, d.cases.size(), 2, 100000, diag);
  if (node["target_nrmse"]) {
    const sm_param_v1 p = {"target_nrmse", SM_NUMBER, "-", 0, 100, 0, nullptr, 0, nullptr, ""};
    auto v = validate_value(p, node["target_nrmse"], file, key_path + ".target_nrmse", diag);
    if (v.is_number()) d.target_nrmse = v;
  }
  if (node["fidelity"]) parse_fidelity(node["fidelity"], file, key_path + ".fidelity", scene, registry, d, diag);
}

// `samples` points, seeded: each variable's [min, max] cut into `samples` strata, one point in each,
// the strata of the variables paired by independent random permutations.
void add_latin_hypercube_cases(const YAML::Node &node, const std::string &file, const std::string &key_path, Design &d,
                               Diagnostics &diag) {
  const std::size_t nv = d.variables.size();
  const std::size_t samples = read_design_integer(node, "samples", file, key_path, 10, 1, 100000, diag);
  const std::size_t seed = read_design_integer(node, "seed", file, key_path, 1, 0, 4294967295ull, diag);
  for (const auto &v : d.variables)
    if (v.values.size() != 2)
      diag.error(Location::of(file, node[v.key.name]), key_path + "." + v.key.name,
                 "a latin_hypercube variable takes [min, max]");
  if (!diag.empty()) return;
  std::mt19937_64 rng(seed);
  auto uniform = [&] { return double(rng() >> 11) * (1.0 / 9007199254740992.0); };
  std::vector<std::vector<double>> cols(nv);
  for (std::size_t k = 0; k < nv; ++k) {
    std::vector<std::size_t> perm(samples);
    for (std::size_t i = 0; i < samples; ++i) perm[i] = i;
    for (std::size_t i = samples; i-- > 1;) std::swap(perm[i], perm[rng() % (i + 1)]);
    for (std::size_t i = 0; i < samples; ++i) {
      const double u = (perm[i] + uniform()) / double(samples);
      cols[k].push_back(d.variables[k].values[0] + u * (d.variables[k].values[1] - d.variables[k].values[0]));
    }
  }
  for (std::size_t i = 0; i < samples; ++i) {
    std::vector<double> row(nv);
    for (std::size_t k = 0; k < nv; ++k) row[k] = cols[k][i];
    d.cases.push_back(row);
  }
}

// A list design's variables: the keys of its first case.
void read_list_variables(const YAML::Node &first, const std::string &file, const std::string &key_path,
                         const Scene &scene, PluginRegistry &registry, Design &d, Diagnostics &diag) {
  for (const auto &kv : first) {
    DesignVariable var;
    std::string why;
    const std::string name = kv.first.as<std::string>();
    if (!find_scene_key(scene, registry, name, var.key, why)) {
      diag.error(Location::of(file, kv.first), key_path + ".cases[0]." + name, why);
      continue;
    }
    d.variables.push_back(var);
  }
}

// A key case i has and the first case does not (a typo, most often): named, with the nearest variable.
void report_keys_not_in_first_case(const YAML::Node &one, std::size_t i, const std::string &file,
                                   const std::string &key_path, const Design &d, Diagnostics &diag) {
  std::vector<std::string> known;
  for (const auto &var : d.variables) known.push_back(var.key.name);
  if (one.IsMap())
    for (const auto &kv : one) {
      const std::string name = kv.first.as<std::string>();
      if (std::find(known.begin(), known.end(), name) != known.end() || i == 0) continue;
      const std::string near = closest(name, known);
      diag.error(Location::of(file, kv.first), key_path + ".cases[" + std::to_string(i) + "]." + name,
                 "not a variable of the first case (every case names the same variables)",
                 near.empty() ? "the first case names: " + join(known) : "did you mean '" + near + "'?");
    }
}

// `cases: [{U: 40 mm/s, omega: 0}, ...]`, each case naming the same variables. False (reported)
// when there are no cases.
bool add_listed_cases(const YAML::Node &node, const std::string &file, const std::string &key_path, const Scene &scene,
                      PluginRegistry &registry, Design &d, Diagnostics &diag) {
  const YAML::Node cases = node["cases"];
  if (!cases || !cases.IsSequence() || cases.size() == 0) {
    diag.error(Location::of(file, node), key_path + ".cases",
               "a list design needs cases: [{U: 40 mm/s, omega: 0}, ...]");
    return false;
  }
  read_list_variables(cases[0], file, key_path, scene, registry, d, diag);
  for (std::size_t i = 0; i < cases.size(); ++i) {
    std::vector<double> row;
    for (const auto &var : d.variables) {
      const YAML::Node v = cases[i][var.key.name];
      const std::string path = key_path + ".cases[" + std::to_string(i) + "]." + var.key.name;
      if (!v) {
        diag.error(Location::of(file, cases[i]), path, "missing (every case names the same variables)");
        row.push_back(0);
        continue;
      }
      auto j = validate_value(*var.key.param, v, file, path, diag);
      row.push_back(j.is_number() ? j.get<double>() : 0.0);
    }
    d.cases.push_back(row);
    report_keys_not_in_first_case(cases[i], i, file, key_path, d, diag);
  }
  return true;
}

}  // namespace

Design parse_design(const YAML::Node &node, const std::string &file, const std::string &key_path, const Scene &scene,
                    PluginRegistry &registry, Diagnostics &diag) {
  Design d;
  if (!node || node.IsNull()) {
    d.cases.push_back({});  // the scene itself, one case
    return d;
  }
  if (!node.IsMap()) {
    diag.error(Location::of(file, node), key_path,
               "expected a mapping: {type: full_factorial, U: [...], omega: [...]}");
    return d;
  }
  const std::optional<DesignType> type = read_design_type(node, file, key_path, d, diag);
  if (!type) return d;
  read_design_variables(node, file, key_path, scene, registry, d, diag);
  const std::size_t nv = d.variables.size();
  switch (*type) {
    case DesignType::full_factorial:
      add_full_factorial_cases(d);
      break;
    case DesignType::adaptive:  // its candidates: the full factorial's cases
      add_full_factorial_cases(d);
      read_adaptive_settings(node, file, key_path, scene, registry, d, diag);
      break;
    case DesignType::latin_hypercube:
      add_latin_hypercube_cases(node, file, key_path, d, diag);
      break;
    case DesignType::list:
      if (!add_listed_cases(node, file, key_path, scene, registry, d, diag)) return d;
      break;
  }
  if (d.cases.empty() && nv == 0) d.cases.push_back({});
  return d;
}

Scene case_scene(const Scene &scene, const Design &design, std::size_t index, bool cheap) {
  Scene s = scene;
  for (std::size_t k = 0; k < design.variables.size(); ++k)
    apply_scene_value(s, design.variables[k].key, design.cases[index][k]);
  if (cheap)
    for (const auto &c : design.cheap) apply_scene_value(s, c.key, c.values.front());
  return s;
}

nlohmann::json case_inputs(const Design &design, std::size_t index) {
  nlohmann::json in = nlohmann::json::object();
  for (std::size_t k = 0; k < design.variables.size(); ++k) in[design.variables[k].key.name] = design.cases[index][k];
  return in;
}

}  // namespace spreadmap
