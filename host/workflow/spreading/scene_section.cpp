#include "workflow/spreading/scene_section.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>
#include <spreadmap/params.hpp>
#include <nlohmann/json.hpp>
#include <yaml-cpp/yaml.h>

#include "core/error.hpp"
#include "core/schema.hpp"
#include "core/suggest.hpp"
#include "workflow/spreading/cohesion_check.hpp"
#include "workflow/spreading/spreader_check.hpp"
#include "workflow/spreading/layers_check.hpp"
#include "workflow/spreading/machine_check.hpp"
#include "workflow/spreading/powder_cost.hpp"
#include "workflow/spreading/powder_sizes.hpp"
#include "workflow/spreading/presets.hpp"
#include "workflow/spreading/size_table.hpp"
#include "workflow/spreading/substrate_height_map.hpp"
#include "workflow/spreading/substrate_roughness.hpp"

namespace spreadmap {
namespace sm = spreadmap;
namespace {

constexpr sm_param_v1 domain_params[] = {
    sm::number("length", "m", 1e-3, 10, 0.04, "extent along x, the spreading direction (x from 0)"),
    sm::number("width", "m", 1e-4, 10, 2.5e-3, "extent along y, across the spreading direction (y from 0)"),
    sm::number("height", "m", 1e-3, 10, 0.015, "extent along z above the substrate (z from 0)"),
    sm::boolean("periodic_x", false, "periodic along x (usually not: particles leave and are counted)"),
    sm::boolean("periodic_y", true, "periodic along y: a strip stands for the full spreader length"),
};

constexpr sm_param_v1 powder_params[] = {
    sm::number("diameter", "m", 1e-6, 0.1, 250e-6, "sphere diameter (monodisperse) phi"),
    sm::number("density", "kg/m^3", 1, 1e5, 4430, "material density rho (Ti-6Al-4V 4430)"),
    sm::integer("count", 0, 1e8, 1600, "number of spheres in the heap (ignored when volume > 0)"),
    sm::number("volume", "m^3", 0, 1, 0, "solid powder volume of the heap; 0 = use count"),
    sm::enumeration("distribution", "mono|lognormal|normal|table", "mono",
                    "size distribution: mono (diameter), lognormal, normal or table"),
    sm::enumeration("basis", "number|volume|mass", "number",
                    "what d10/d50/d90 and table fractions count: particles, or their volume (= mass)"),
    sm::number("d10", "m", 0, 0.1, 0, "lognormal/normal: D10, with d50 and d90 (least-squares fit); 0 = not given"),
    sm::number("d50", "m", 1e-6, 0.1, 250e-6, "lognormal: median D50 (with sigma, or d10 and d90); normal: mean"),
    sm::number("d90", "m", 0, 0.1, 0, "lognormal/normal: D90, with d10 and d50; 0 = not given"),
    sm::number("sigma", "-", 0, 2, 0.1, "lognormal: standard deviation of ln(d) (or give d10 and d90)"),
    sm::number("standard_deviation", "m", 0, 0.1, 0, "normal: standard deviation of d (or give d10 and d90)"),
    sm::number("d_min", "m", 0, 0.1, 0,
               "lognormal/normal: smallest diameter (truncation, redrawn); 0 = d50 x exp(-3 sigma) or d50 - 3 std"),
    sm::number("d_max", "m", 0, 0.1, 0,
               "lognormal/normal: largest diameter (truncation, redrawn); 0 = d50 x exp(3 sigma) or d50 + 3 std"),
    sm::table("table",
              "table: rows {diameter, fraction} or {from, to, fraction} (size classes), or a CSV file with those "
              "columns; fractions by basis, summing to 1"),
    sm::integer("seed", 0, 4294967295.0, 1, "random seed of the heap insertion"),
    sm::number("heap_from", "m", 0, 10, 6e-3, "x where the heap starts (behind it: the spreader)"),
    sm::number("heap_to", "m", 0, 10, 13e-3, "x where the heap ends (a temporary wall while settling)"),
    sm::number("heap_top", "m", 0, 10, 0, "insertion height limit; 0 = the domain height minus one diameter"),
    sm::number("settle_time", "s", 0, 100, 0.1, "settling time under gravity before the spreader moves"),
    sm::number("settle_speed", "m/s", 0, 10, 1e-3, "settling stops early once the fastest sphere is slower"),
    sm::number("settle_fraction", "-", 0.5, 1, 1,
               "settling stops early once this fraction of the spheres is slower than settle_speed (1: all; "
               "0.99 lets a few rattlers on soft, bouncy contacts bounce on)"),
    sm::number("coarse_grain", "-", 1, 10, 1,
               "coarse graining k: spheres k x larger, k^3 fewer, contact lengths (overlap_max) x k"),
};

constexpr sm_param_v1 time_params[] = {
    sm::number("step", "s", 0, 1, 0, "time step dt; 0 = automatic (safety x the stable limit dt_crit)"),
    sm::number("safety", "-", 1e-3, 1, 0.4, "automatic step as a fraction of dt_crit"),
    sm::number("skin", "m", 0, 0.1, 0, "neighbour-list skin; 0 = 0.2 x the largest diameter"),
    sm::number("relax", "s", 0, 100, 0.01, "time after the spreader stops before the final state"),
    sm::number("checkpoint_interval", "s", 1, 1e6, 60, "wall-clock seconds between checkpoints"),
    sm::integer("snapshots", 0, 100000, 0, "states written during spreading (series.pvd); 0 = final only"),
    sm::number("overlap_limit", "-", 1e-4, 1, 0.1, "largest overlap allowed, as a fraction of the diameter"),
    sm::boolean("sleep", false, "particles at rest far behind the spreader stop being integrated until touched"),
    sm::number("sleep_speed", "m/s", 1e-9, 1, 1e-3, "sleep: slower than this (spin included) counts as at rest"),
    sm::number("sleep_behind", "m", 0, 10, 5e-3, "sleep: only this far behind the spreader's trailing edge"),
};

constexpr sm_param_v1 layers_params[] = {
    sm::integer("count", 1, 50, 1, "layers spread one upon the other; 1 = one pass onto the plate"),
    sm::number("thickness", "m", 1e-7, 0.1, 50e-6, "layer thickness: the platform's drop before each further pass"),
};

constexpr sm_param_v1 machine_params[] = {
    sm::number("reservoir_from", "m", 0, 10, 6e-3, "x where the feed's reservoir starts (behind it: a plate the spreader rests over)"),
    sm::number("reservoir_length", "m", 1e-5, 10, 5e-3, "the reservoir's length along x"),
    sm::number("reservoir_depth", "m", 1e-5, 1, 4e-3,
               "the piston's starting depth below the plates: the powder the feed holds"),
    sm::number("plate_length", "m", 0, 10, 1e-3, "the transfer plate between the reservoir and the well"),
    sm::number("well_length", "m", 1e-6, 10, 10e-3, "the build platform's length along x"),
    sm::number("lip_length", "m", 0, 10, 1e-3, "the plate between the well and the overflow"),
    sm::number("dosing", "-", 0.1, 100, 2,
               "the piston's rise per layer over the layer thickness (below 1 the layer cannot fill)"),
    sm::number("stroke_speed", "m/s", 1e-6, 10, 5e-3, "the speed the platform drops and the piston rises at"),
    sm::number("sleep_depth", "m", 0, 1, 0,
               "with time.sleep: spheres at rest deeper than this below the fresh layer's bottom (the plates less "
               "one layer) may sleep; 0 = none by depth"),
};

constexpr sm_param_v1 roughness_params[] = {
    sm::required_number("rq", "m", 0, 0.01,
                        "R_q of the substrate: root-mean-square height of its spheres' tops about their mean plane"),
    sm::required_number("correlation_length", "m", 1e-9, 1,
                        "correlation length xi: the lag at which the tops' autocorrelation falls to 1/e (at least 2 "
                        "sphere diameters)"),
    sm::number("sphere_diameter", "m", 0, 0.1, 0,
               "diameter (and spacing) of the substrate's fixed spheres; 0 = the powder's D50 by volume"),
};

constexpr sm_param_v1 engine_params[] = {
    sm::enumeration("preset", "quick|standard|paper|paper_full", "quick", "fidelity preset the other keys override"),
    sm::enumeration("precision", "double|float", "double", "floating-point precision of the particle state"),
    sm::enumeration("backend", "auto|cpu|cuda", "auto", "where the DEM runs (auto: a GPU when present)"),
    sm::integer("threads", 0, 1024, 0, "OpenMP threads; 0 = all cores"),
    sm::boolean("deterministic", true, "results independent of thread count, bitwise run to run"),
    sm::number("gravity", "m/s^2", 0, 1000, 9.81, "gravitational acceleration along -z"),
};

struct Section {
  const char *name;
  const sm_param_v1 *params;
  std::size_t n;
};
constexpr Section host_sections[] = {
    {"domain", domain_params, std::size(domain_params)},
    {"powder", powder_params, std::size(powder_params)},
    {"time", time_params, std::size(time_params)},
    {"layers", layers_params, std::size(layers_params)},
};

const std::vector<std::string> scene_keys = {"preset",    "precision", "backend", "threads", "deterministic",
                                             "gravity",   "domain",    "powder",  "time",    "contact",
                                             "substrate", "spreader",  "layers",  "machine"};

// The preset's node for a section, overlaid with the user's node (user keys win).
YAML::Node overlay(const YAML::Node &preset, const YAML::Node &user) {
  YAML::Node out(YAML::NodeType::Map);
  if (preset && preset.IsMap())
    for (const auto &kv : preset) out[kv.first.as<std::string>()] = kv.second;
  if (user && user.IsMap())
    for (const auto &kv : user) out[kv.first.as<std::string>()] = kv.second;
  return out;
}

// The keys of `node` that one of the schemas declares. A preset is written for the plugins it names
// (presets/*.yaml); when the user picks another plugin, the preset's values apply only where
// that plugin has the key. The user's own spreader keys are split this way between geometry and law.
YAML::Node known_only(const YAML::Node &node, const SchemaView &a, const SchemaView &b = {}) {
  YAML::Node out(YAML::NodeType::Map);
  if (node && node.IsMap())
    for (const auto &kv : node) {
      const std::string key = kv.first.as<std::string>();
      if (a.find(key) || b.find(key)) out[key] = kv.second;
    }
  return out;
}

// Validates a section key by key, reporting positions in the file each key came from.
nlohmann::json validate_split(const SchemaView &schema, const YAML::Node &preset, const YAML::Node &user,
                              const std::string &scene_file, const std::string &section, Diagnostics &diag,
                              const std::set<std::string> &skip = {}) {
  const std::string preset_label = "<preset>";
  auto values = validate_params(schema, preset, preset_label, section, diag, skip, false);
  if (user && user.IsDefined() && !user.IsNull()) {
    auto mine = validate_params(schema, user, scene_file, section, diag, skip, false);
    for (auto &[k, v] : mine.items()) values[k] = v;
  }
  fill_defaults(schema, values, Location::of(scene_file, user ? user : preset), section, diag);
  return values;
}

// Checks across keys that no single schema entry can express; each names the key the user wrote
// (or the section, when the value came from the preset).
void check_consistency(const nlohmann::json &scene, const YAML::Node &user, const std::string &file,
                       Diagnostics &diag) {
  auto where = [&](const char *section, const char *key) {
    const YAML::Node sec = user[section];
    if (sec && sec.IsMap() && sec[key]) return Location::of(file, sec[key]);
    return Location::of(file, sec ? sec : user);
  };
  auto number = [&](const char *section, const char *key, double &out) {
    const auto &sec = scene.contains(section) ? scene[section] : nlohmann::json();
    if (!sec.is_object() || !sec.contains(key) || !sec[key].is_number()) return false;
    out = sec[key].get<double>();
    return true;
  };
  double count, volume, from, to, length, height;
  if (number("powder", "count", count) && number("powder", "volume", volume) && count < 1 && volume <= 0)
    diag.error(where("powder", "count"), "scene.powder.count", "no powder: count is 0 and no volume is given",
               "give count >= 1 (spheres) or volume > 0 (solid volume of the heap)");
  if (number("powder", "heap_from", from) && number("powder", "heap_to", to) && from >= to)
    diag.error(where("powder", "heap_to"), "scene.powder.heap_to",
               fmt::format("the heap ends at x = {:g} m, not after its start heap_from = {:g} m", to, from));
  if (number("powder", "heap_to", to) && number("domain", "length", length) && to > length)
    diag.error(where("powder", "heap_to"), "scene.powder.heap_to",
               fmt::format("the heap ends at x = {:g} m, beyond the domain (length {:g} m)", to, length));
  const auto &spreader = scene.contains("spreader") ? scene["spreader"] : nlohmann::json();
  if (spreader.is_object() && spreader.contains("params") && spreader["params"].contains("gap") &&
      spreader["params"]["gap"].is_number() && number("domain", "height", height) &&
      spreader["params"]["gap"].get<double>() >= height)
    diag.error(where("spreader", "gap"), "scene.spreader.gap",
               fmt::format("the gap ({:g} m) is not below the top of the domain (height {:g} m): the spreader would "
                           "pass above everything",
                           spreader["params"]["gap"].get<double>(), height));
}

// A plugin's own checks across its parameters (its bind()) run now, before any work starts, so that a
// refusal points at the workflow's section rather than surfacing in the middle of a run.
void probe_plugins(const nlohmann::json &scene, const LoadedPlugin &law, const LoadedPlugin &geo,
                   const YAML::Node &user, const std::string &file, Diagnostics &diag) {
  auto section = [&](const char *name) { return Location::of(file, user[name] ? user[name] : user); };
  auto probe = [&](const LoadedPlugin &plugin, const nlohmann::json &params, const char *name) {
    try {
      PluginInstance instance(plugin, params.dump());
      return true;
    } catch (const PluginError &e) {
      diag.error(section(name), std::string("scene.") + name, e.what());
      return false;
    }
  };
  // the substrate and spreader laws inherit the contact's values: a refusal there is reported once
  if (probe(law, scene["contact"]["params"], "contact")) {
    probe(law, scene["substrate"]["law"], "substrate");
    probe(law, scene["spreader"]["law"], "spreader");
  }
  probe(geo, scene["spreader"]["params"], "spreader");
}

// The size distribution's keys; once they and the rest of the scene are valid, its warnings, said
// once (validate and run resolve the scene once).
void check_powder(const Scene &scene, const YAML::Node &powder, const std::string &file, PluginRegistry &registry,
                  Diagnostics &diag) {
  std::vector<std::string> warnings = check_powder_sizes(scene.powder, powder, file, diag);
  if (!diag.empty()) return;
  try {
    if (auto cost = powder_cost_warning(scene, registry, file)) warnings.push_back(*cost);
  } catch (const std::exception &e) {  // an estimate only: the run reports real problems itself
    spdlog::debug("the cost of the scene could not be estimated: {}", e.what());
  }
  for (const auto &w : warnings) spdlog::warn("{}", w);
}

// A top-level key the scene does not know, named with the nearest known one.
void report_unknown_scene_keys(const YAML::Node &user, const std::string &file, Diagnostics &diag) {
  for (const auto &kv : user) {
    const std::string key = kv.first.as<std::string>();
    if (std::find(scene_keys.begin(), scene_keys.end(), key) == scene_keys.end()) {
      const std::string near = closest(key, scene_keys);
      diag.error(Location::of(file, kv.first), "scene." + key, "unknown key",
                 (near.empty() ? "" : "did you mean '" + near + "'? ") + "known: " + join(scene_keys));
    }
  }
}

// The top-level engine keys (preset, precision, backend, ...), checked by their schema.
nlohmann::json read_engine_keys(const YAML::Node &user, const std::string &file, Diagnostics &diag) {
  YAML::Node top(YAML::NodeType::Map);
  for (const auto &kv : user)
    if (SchemaView{engine_params, std::size(engine_params)}.find(kv.first.as<std::string>())) top[kv.first] = kv.second;
  return validate_params({engine_params, std::size(engine_params)}, top, file, "scene", diag);
}

// The host's own sections (domain, powder, time, layers): the preset's values, the user's over them.
void read_host_sections(const YAML::Node &preset, const YAML::Node &user, const std::string &file,
                        nlohmann::json &scene, Diagnostics &diag) {
  for (const auto &s : host_sections) {
    const YAML::Node preset_section =
        preset[s.name] ? preset[s.name] : YAML::Node(YAML::NodeType::Map);  // layers: none
    scene[s.name] =
        validate_split({s.params, s.n}, preset_section, user[s.name], file, std::string("scene.") + s.name, diag);
  }
}

// The plugin a section names with `use:` (scene.contact or scene.spreader); null when there is none
// of that name (reported at the user's `use:`, or at the scene when the preset named it).
const LoadedPlugin *section_plugin(PluginRegistry &registry, const char *section, const std::string &name,
                                   const YAML::Node &user, const std::string &file, Diagnostics &diag) {
  try {
    return &registry.get(section, name);
  } catch (const std::exception &e) {
    diag.error(Location::of(file, user[section] && user[section]["use"] ? user[section]["use"] : user),
               std::string("scene.") + section + ".use", e.what());
  }
  return nullptr;
}

// The plugin's name a section's `use:` gives, the user's over the preset's.
std::string section_use(const YAML::Node &preset, const YAML::Node &user, const char *section) {
  const YAML::Node merged = overlay(preset[section], user[section]);
  return merged["use"] ? merged["use"].as<std::string>() : "";
}

// scene.contact: the particle-particle law's values; returns them (the other laws inherit them).
nlohmann::json read_contact_section(const LoadedPlugin &law, const std::string &law_name, const YAML::Node &preset,
                                    const YAML::Node &user, const std::string &file, nlohmann::json &scene,
                                    Diagnostics &diag) {
  const auto schema = SchemaView::of(*law.descriptor);
  auto pp = validate_split(schema, known_only(preset["contact"], schema), user["contact"], file, "scene.contact", diag,
                           {"use"});
  scene["contact"] = {{"use", law_name}, {"params", pp}};
  return pp;
}

// scene.substrate: the contact law's values with the substrate's overrides (law keys only), and its
// surface: the flat plate, a rough one or a measured height map.
void read_substrate_section(const LoadedPlugin &law, const nlohmann::json &pp, const YAML::Node &preset,
                            const YAML::Node &user, const std::string &file, const fs::path &scene_dir,
                            nlohmann::json &scene, Diagnostics &diag) {
  const auto schema = SchemaView::of(*law.descriptor);
  auto sub =
      validate_params(schema, known_only(preset["substrate"], schema), "<preset>", "scene.substrate", diag, {}, false);
  const YAML::Node user_substrate = user["substrate"];
  if (user_substrate) {
    auto mine =
        validate_params(schema, user_substrate, file, "scene.substrate", diag, {"roughness", "height_map"}, false);
    for (auto &[k, v] : mine.items()) sub[k] = v;
  }
  nlohmann::json sub_law = pp;
  for (auto &[k, v] : sub.items()) sub_law[k] = v;
  scene["substrate"] = {{"law", sub_law}};
  const bool substrate_map = user_substrate && user_substrate.IsMap();  // neither key: the flat plate
  if (substrate_map && user_substrate["roughness"] && user_substrate["height_map"])
    diag.error(Location::of(file, user_substrate["height_map"]), "scene.substrate.height_map",
               "a substrate is either rough (roughness: a random surface) or measured (height_map), not both",
               "remove roughness or height_map");
  else if (substrate_map && user_substrate["roughness"])
    scene["substrate"]["roughness"] =
        validate_params({roughness_params, std::size(roughness_params)}, user_substrate["roughness"], file,
                        "scene.substrate.roughness", diag);
  else if (substrate_map && user_substrate["height_map"])
    scene["substrate"]["height_map"] = resolve_height_map(user_substrate["height_map"], file, scene_dir, diag);
}

// scene.spreader: geometry keys go to the geometry, law keys to the particle-spreader law (the
// contact law's values with the spreader's overrides).
void read_spreader_section(const LoadedPlugin &law, const LoadedPlugin &geo, const std::string &geo_name,
                           const nlohmann::json &pp, const YAML::Node &preset, const YAML::Node &user,
                           const std::string &file, nlohmann::json &scene, Diagnostics &diag) {
  const auto schema = SchemaView::of(*law.descriptor);
  const auto gschema = SchemaView::of(*geo.descriptor);
  std::set<std::string> law_keys;
  for (std::size_t i = 0; i < schema.n; ++i) law_keys.insert(schema.params[i].name);
  auto gvals = validate_split(gschema, known_only(preset["spreader"], gschema, schema), user["spreader"], file,
                              "scene.spreader", diag, [&] {
                                auto k = law_keys;
                                k.insert("use");
                                return k;
                              }());
  // law keys only: a key neither plugin knows was reported once, by the geometry above
  nlohmann::json spr_law = pp;
  auto lp =
      validate_params(schema, known_only(preset["spreader"], schema), "<preset>", "scene.spreader", diag, {}, false);
  for (auto &[k, v] : lp.items()) spr_law[k] = v;
  if (user["spreader"] && user["spreader"].IsMap()) {
    auto mine = validate_params(schema, known_only(user["spreader"], schema), file, "scene.spreader", diag, {}, false);
    for (auto &[k, v] : mine.items()) spr_law[k] = v;
  }
  scene["spreader"] = {{"use", geo_name}, {"params", gvals}, {"law", spr_law}};
}

// The scene typed, then the checks that need it whole (each once the ones before it pass).
std::optional<Scene> typed_and_checked(const nlohmann::json &scene, const YAML::Node &powder, const YAML::Node &user,
                                       const std::string &file, PluginRegistry &registry, Diagnostics &diag) {
  std::optional<Scene> typed;
  try {
    typed = scene_from_json(scene, file);
  } catch (const InputError &) {
    if (diag.empty()) throw;  // a valid scene always types: this would be a bug here, not the user's
    return std::nullopt;      // its problems are reported already
  }
  check_powder(*typed, powder, file, registry, diag);
  if (diag.empty()) check_layers(*typed, user, file, registry, diag);
  if (diag.empty()) check_machine(*typed, user, file, registry, diag);
  if (diag.empty()) check_roughness(*typed, user, file, registry, diag);
  if (diag.empty()) check_cohesion(*typed, user, file, registry, diag);
  if (diag.empty()) check_spreader_span(*typed, user, file, registry, diag);
  return typed;
}

}  // namespace

const char *preset_text(const std::string &preset) {
  if (preset == "standard") return presets::standard;
  if (preset == "paper") return presets::paper;
  if (preset == "paper_full") return presets::paper_full;
  return presets::quick;
}

std::optional<Scene> resolve_scene(const Workflow &wf, PluginRegistry &registry, Diagnostics &diag) {
  const std::string &file = wf.scene_file;
  const YAML::Node &user = wf.scene;
  nlohmann::json scene = nlohmann::json::object();
  report_unknown_scene_keys(user, file, diag);
  const nlohmann::json engine = read_engine_keys(user, file, diag);
  scene.update(engine);
  // an invalid preset was reported above; go on with quick to report the other problems too
  const std::string preset =
      engine.contains("preset") && engine["preset"].is_string() ? engine["preset"].get<std::string>() : "quick";
  const YAML::Node p = YAML::Load(preset_text(preset));

  read_host_sections(p, user, file, scene, diag);
  if (user["machine"])  // no preset has one: the heap on a plate unless the user describes a machine
    scene["machine"] = validate_split({machine_params, std::size(machine_params)}, YAML::Node(YAML::NodeType::Map),
                                      user["machine"], file, "scene.machine", diag);
  const YAML::Node powder = user["powder"] && user["powder"].IsMap() ? user["powder"] : YAML::Node();
  const fs::path scene_dir = fs::path(file).has_parent_path() ? fs::path(file).parent_path() : fs::path(".");
  resolve_size_table(scene["powder"], powder["table"], file, scene_dir, diag);

  // contact law: particle-particle, then substrate and spreader overrides of the same law
  const std::string law_name = section_use(p, user, "contact");
  const LoadedPlugin *law = section_plugin(registry, "contact", law_name, user, file, diag);
  const std::string geo_name = section_use(p, user, "spreader");
  const LoadedPlugin *geo = section_plugin(registry, "spreader", geo_name, user, file, diag);
  if (law) {
    const nlohmann::json pp = read_contact_section(*law, law_name, p, user, file, scene, diag);
    read_substrate_section(*law, pp, p, user, file, scene_dir, scene, diag);
    if (geo) read_spreader_section(*law, *geo, geo_name, pp, p, user, file, scene, diag);
  }
  check_consistency(scene, user, file, diag);
  if (diag.empty() && law && geo) probe_plugins(scene, *law, *geo, user, file, diag);
  return typed_and_checked(scene, powder, user, file, registry, diag);
}

bool find_scene_key(const Scene &scene, PluginRegistry &registry, const std::string &name, SceneKey &out,
                    std::string &why) {
  std::string section, key;
  static const std::map<std::string, std::pair<std::string, std::string>> aliases = {{"U", {"spreader", "U"}},
                                                                                     {"omega", {"spreader", "omega"}},
                                                                                     {"gap", {"spreader", "gap"}},
                                                                                     {"seed", {"powder", "seed"}}};
  if (auto it = aliases.find(name); it != aliases.end()) {
    section = it->second.first;
    key = it->second.second;
  } else if (auto dot = name.find('.'); dot != std::string::npos) {
    section = name.substr(0, dot);
    key = name.substr(dot + 1);
  } else if (name == "precision" || name == "gravity") {  // the top-level keys that change a case's result
    out = {name, "", name, false, SchemaView{engine_params, std::size(engine_params)}.find(name)};
    return true;
  } else {
    why = "unknown design variable '" + name +
          "': write U, omega, gap, seed or a dotted scene key such as contact.friction";
    return false;
  }
  out = {name, section, key, false, nullptr};
  for (const auto &s : host_sections)
    if (section == s.name) {
      if ((out.param = SchemaView{s.params, s.n}.find(key))) return true;
      why = "scene." + section + " has no key '" + key + "'";
      return false;
    }
  if (section == "machine") {
    if ((out.param = SchemaView{machine_params, std::size(machine_params)}.find(key))) return true;
    why = "scene.machine has no key '" + key + "'";
    return false;
  }
  if (section == "contact" || section == "spreader" || section == "substrate") {
    if (section == "spreader" &&
        (out.param = SchemaView::of(*registry.get("spreader", scene.spreader.use).descriptor).find(key)))
      return true;
    if ((out.param = SchemaView::of(*registry.get("contact", scene.contact.use).descriptor).find(key))) {
      out.spreader_law = section == "spreader";
      return true;
    }
    why = "scene." + section + " has no key '" + key + "'";
    return false;
  }
  why = "unknown scene section '" + section + "' in design variable '" + name + "'";
  return false;
}

}  // namespace spreadmap
