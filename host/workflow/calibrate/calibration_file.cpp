#include "workflow/calibrate/calibration_file.hpp"

#include <fmt/format.h>
#include <spreadmap/params.hpp>
#include <nlohmann/json.hpp>
#include <yaml-cpp/yaml.h>

#include "core/error.hpp"
#include "core/schema.hpp"
#include "core/suggest.hpp"
#include "workflow/scene/scene_build.hpp"
#include "workflow/stage/plugin_needs.hpp"
#include "workflow/file/workflow.hpp"

namespace spreadmap::calibrate {
namespace sm = spreadmap;
namespace {

constexpr double deg = 3.14159265358979323846 / 180;

constexpr sm_param_v1 top_params[] = {
    sm::integer("version", 1, 1, 1, "format version of the calibration file: 1"),
    sm::text("name", "calibration", "the calibration's name: the default output folder is runs/<name>"),
    sm::table("parameters", "contact-law keys to identify, each with its range [lo, hi]"),
    sm::table("design", "the simulations: levels per parameter (full factorial)"),
    sm::table("tests", "the bulk tests: a list of {scene, measure, angle, uncertainty}"),
    sm::table("model", "the surrogate plugin (use: NAME) and its parameters; default: the first that gives a "
             "predictive standard deviation"),
};

constexpr sm_param_v1 design_params[] = {
    sm::integer("levels", 2, 9, 3, "values per parameter, evenly spaced over its range (levels^parameters runs)"),
};

constexpr sm_param_v1 test_params[] = {
    sm::text("scene", "", "the bulk test's scene file (docs/scenes.md), relative to this file"),
    sm::text("name", "", "name in messages and outputs (default: the scene file's stem)"),
    sm::enumeration("measure", "heap_angle|drum_angle", "heap_angle",
                    "heap_angle: a cone on a plate (lifted cylinder); drum_angle: the free surface in a drum "
                    "turning about y"),
    sm::number("plate_z", "m", -100, 100, 0, "heap_angle: height of the plate the heap stands on"),
    sm::number("angle", "rad", 0.1 * deg, 89.9 * deg, 0,
               "the angle measured on the real powder, e.g. 32 deg (omit to only simulate)"),
    sm::number("uncertainty", "rad", 0.01 * deg, 45 * deg, 1 * deg, "its standard uncertainty, e.g. 1 deg"),
};

// The contact law of a test's scene: its plugin and parameters, as the scene file gives them.
struct SceneLaw {
  const LoadedPlugin *plugin = nullptr;
  nlohmann::json params;
};

// tests: each scene read whole (its own errors are its file's), its contact law kept for the ranges.
// The nodes are not const: a missing key reads as undefined, not invalid.
std::vector<SceneLaw> read_bulk_tests(YAML::Node root, YAML::Node tests, const std::string &file, CalibrationFile &c,
                                      PluginRegistry &registry, Diagnostics &diag) {
  std::vector<SceneLaw> laws;
  if (!tests || !tests.IsSequence() || tests.size() == 0)
    diag.error(Location::of(file, tests ? tests : root), "tests", "expected a list of bulk tests",
               "add tests: [{scene: repose.yaml, measure: heap_angle, angle: 32 deg, uncertainty: 1 deg}]");
  for (std::size_t k = 0; tests && tests.IsSequence() && k < tests.size(); ++k) {
    const std::string key = fmt::format("tests[{}]", k);
    const auto v = validate_params({test_params, std::size(test_params)}, tests[k], file, key, diag);
    if (!v.contains("scene") || !v["scene"].is_string()) continue;
    if (v["scene"].get<std::string>().empty()) {
      diag.error(Location::of(file, tests[k]), key + ".scene", "required value missing",
                 "give the bulk test's scene file, e.g. scene: repose.yaml");
      continue;
    }
    BulkTest t;
    t.where = Location::of(file, tests[k]);
    t.scene = fs::absolute(c.file.parent_path() / v["scene"].get<std::string>());
    t.name = v.value("name", std::string());
    if (t.name.empty()) t.name = t.scene.stem().string();
    t.measure =
        v.value("measure", std::string("heap_angle")) == "drum_angle" ? Measure::drum_angle : Measure::heap_angle;
    t.plate_z = v.value("plate_z", 0.0);
    t.measured = tests[k]["angle"].IsDefined();
    t.angle_deg = v.value("angle", 0.0) / deg;
    t.sigma_deg = v.value("uncertainty", 0.0) / deg;
    if (!fs::exists(t.scene)) {
      diag.error(Location::of(file, tests[k]["scene"]), key + ".scene", "no such file: " + t.scene.string(),
                 "give the scene file's path relative to " + c.file.parent_path().string());
      continue;
    }
    try {
      const auto scene = scene::load_scene(t.scene, registry);
      laws.push_back({&registry.get("contact", scene.scene.law), scene.scene.pair_law});
    } catch (const InputError &e) {
      diag.error(Location::of(file, tests[k]["scene"]), key + ".scene", "the scene file has errors (below)");
      for (const auto &m : e.messages) diag.error(m);
      continue;
    }
    c.tests.push_back(std::move(t));
  }
  return laws;
}

// One parameter's range [lo, hi], checked against every test's contact law; kept (from the first
// law's schema) when every law takes it.
void read_parameter_range(const std::string &name, YAML::Node name_node, YAML::Node range,
                          const std::vector<SceneLaw> &laws, const std::string &file, CalibrationFile &c,
                          Diagnostics &diag) {
  const std::string key = "parameters." + name;
  if (!range.IsSequence() || range.size() != 2) {
    diag.error(Location::of(file, range), key, "expected a range [lo, hi]", "write e.g. " + name + ": [0.2, 0.8]");
    return;
  }
  for (const SceneLaw &law : laws) {
    const SchemaView schema = SchemaView::of(*law.plugin->descriptor);
    const sm_param_v1 *p = schema.find(name);
    if (!p || p->type != SM_NUMBER) {
      std::vector<std::string> names;
      for (std::size_t i = 0; i < schema.n; ++i)
        if (schema.params[i].type == SM_NUMBER) names.push_back(schema.params[i].name);
      diag.error(Location::of(file, name_node), key,
                 fmt::format("contact/{} has no number parameter '{}'", law.plugin->descriptor->name, name),
                 closest(name, names).empty() ? "numbers it takes: " + join(names)
                                              : "did you mean '" + closest(name, names) + "'?");
      break;
    }
    const auto lo = validate_value(*p, range[0], file, key + "[0]", diag);
    const auto hi = validate_value(*p, range[1], file, key + "[1]", diag);
    if (!lo.is_number() || !hi.is_number()) break;
    if (!(lo.get<double>() < hi.get<double>())) {
      diag.error(Location::of(file, range), key, "the range is empty: lo must be below hi", "swap or widen the bounds");
      break;
    }
    if (&law == &laws.front()) c.parameters.push_back({name, lo.get<double>(), hi.get<double>()});
  }
}

// parameters: keys of every test's contact law, ranges inside the law's own.
void read_parameter_ranges(YAML::Node root, YAML::Node params, const std::vector<SceneLaw> &laws,
                           const std::string &file, CalibrationFile &c, Diagnostics &diag) {
  if (!params || !params.IsMap() || params.size() == 0)
    diag.error(Location::of(file, params ? params : root), "parameters",
               "expected a mapping of contact-law keys to ranges",
               "add parameters: {friction: [0.2, 0.8], rolling_friction: [0, 0.3]}");
  for (auto it = params.IsMap() ? params.begin() : YAML::const_iterator(); params.IsMap() && it != params.end(); ++it)
    read_parameter_range(it->first.as<std::string>(), it->first, it->second, laws, file, c, diag);
}

// The surrogate: model.use and its parameters, checked by its schema. By default the first that gives
// a predictive standard deviation: the fit weighs each test's misfit by it (docs/calibration.md).
void read_surrogate(YAML::Node root, YAML::Node model, const std::string &file, CalibrationFile &c,
                    PluginRegistry &registry, Diagnostics &diag) {
  try {
    const auto &plugin = model && model["use"] ? registry.get("surrogate", model["use"].as<std::string>())
                                               : surrogate_with_std(registry, file + ": the calibration");
    c.model = plugin.descriptor->name;
    c.model_params =
        validate_params(SchemaView::of(*plugin.descriptor), model ? model : YAML::Node(), file, "model", diag, {"use"});
  } catch (const PluginError &e) {
    diag.error(Location::of(file, model ? model["use"] : root), "model.use", e.what());
  }
}

}  // namespace

bool is_calibration_document(const YAML::Node &root) { return root.IsMap() && root["parameters"] && root["tests"]; }

CalibrationFile read_calibration_file(const fs::path &path, PluginRegistry &registry) {
  YAML::Node root = load_yaml(path);  // not const: a missing key reads as undefined, not invalid
  const std::string file = path.string();
  Diagnostics diag;
  CalibrationFile c;
  c.file = fs::absolute(path);
  if (!root.IsMap()) {
    diag.error(Location::of(file, root), "", "a calibration file is a mapping of sections", "see docs/calibration.md");
    diag.throw_if_any();
  }
  const auto top = validate_params({top_params, std::size(top_params)}, root, file, "", diag);
  if (top.contains("name") && top["name"].is_string()) c.name = top["name"].get<std::string>();
  const auto design = validate_params({design_params, std::size(design_params)}, root["design"], file, "design", diag);
  if (design.contains("levels") && design["levels"].is_number()) c.levels = design["levels"].get<int>();

  const std::vector<SceneLaw> laws = read_bulk_tests(root, root["tests"], file, c, registry, diag);
  if (!laws.empty()) c.law = laws.front().plugin->descriptor->name;
  read_parameter_ranges(root, root["parameters"], laws, file, c, diag);
  read_surrogate(root, root["model"], file, c, registry, diag);
  diag.throw_if_any();
  return c;
}

}  // namespace spreadmap::calibrate
