#include "workflow/file/workflow.hpp"

#include <yaml-cpp/depthguard.h>

#include <algorithm>
#include <yaml-cpp/yaml.h>

#include "core/error.hpp"
#include "core/files.hpp"
#include "core/suggest.hpp"

namespace spreadmap {

YAML::Node load_yaml(const fs::path &file) {
  const std::string text = read_text(file);
  try {
    return YAML::Load(text);
  } catch (const YAML::DeepRecursion &e) {  // yaml-cpp calls it "bad file"
    Location at{file.string(), e.mark.line + 1, e.mark.column + 1};
    throw InputError(at.str() + ": YAML nested more than " + std::to_string(e.depth()) +
                     " levels deep here\n  no spreadmap file nests more than a few levels: close the brackets or "
                     "braces opened before this point");
  } catch (const YAML::Exception &e) {
    Location at{file.string(), e.mark.line + 1, e.mark.column + 1};
    throw InputError(at.str() + ": YAML syntax: " + e.msg +
                     "\n  check indentation, colons and brackets on this line or the one before");
  }
}

namespace {

void check_top_keys(const Workflow &wf, const std::string &f, Diagnostics &diag) {
  static const std::vector<std::string> top = {"version", "name", "scene", "stages", "description"};
  for (const auto &kv : wf.root) {
    const std::string key = kv.first.as<std::string>();
    if (std::find(top.begin(), top.end(), key) == top.end()) {
      const std::string near = closest(key, top);
      diag.error(Location::of(f, kv.first), key, "unknown key",
                 (near.empty() ? "" : "did you mean '" + near + "'? ") + "known: " + join(top));
    }
  }
  const YAML::Node version = wf.root["version"];
  if (!version) diag.error(Location::of(f, wf.root), "version", "missing", "add `version: 1` as the first line");
  else if (!version.IsScalar() || version.Scalar() != "1")
    diag.error(Location::of(f, version), "version",
               "this spreadmap reads workflow version 1, not '" +
                   (version.IsScalar() ? version.Scalar() : std::string("?")) + "'");
}

// The run folder's name: `name`, else the file's stem.
std::string read_name(const Workflow &wf, const fs::path &file, Diagnostics &diag) {
  const YAML::Node name = wf.root["name"];
  if (!name || !name.IsScalar() || name.Scalar().empty()) return file.stem().string();
  if (name.Scalar().find_first_of("/\\ ") != std::string::npos)
    diag.error(Location::of(file.string(), name), "name",
               "'" + name.Scalar() + "' cannot name a folder: use letters, digits, - and _");
  return name.Scalar();
}

// `scene`: a mapping, or the name of a scene file relative to the workflow.
void read_scene(Workflow &wf, const std::string &f, Diagnostics &diag) {
  YAML::Node scene = wf.root["scene"];
  wf.scene_file = f;
  if (scene && scene.IsScalar()) {
    const fs::path sf = wf.resolve(scene.Scalar());
    if (!fs::exists(sf)) {
      diag.error(Location::of(f, scene), "scene", "the scene file " + sf.string() + " does not exist",
                 "paths in a workflow are relative to the workflow file's folder");
    } else {
      wf.scene_file = sf.string();
      scene = load_yaml(sf);
    }
  }
  if (scene && !scene.IsMap() && !scene.IsScalar())
    diag.error(Location::of(f, scene), "scene", "expected a mapping (or the name of a scene file)");
  wf.scene = scene && scene.IsMap() ? scene : YAML::Node(YAML::NodeType::Map);
}

// One entry of `stages`: a stage of the table, once, with a mapping of settings.
void read_stage(Workflow &wf, const YAML::Node &s, std::size_t i, const std::vector<std::string> &stage_names,
                const std::string &f, Diagnostics &diag) {
  const std::string path = "stages[" + std::to_string(i) + "]";
  std::string kind;
  YAML::Node config;
  if (s.IsScalar()) {
    kind = s.Scalar();
  } else if (s.IsMap() && s.size() == 1) {
    kind = s.begin()->first.as<std::string>();
    config = s.begin()->second;
  } else {
    diag.error(Location::of(f, s), path, "a stage is one key (" + join(stage_names) + ") with its settings");
    return;
  }
  const YAML::Node key = s.IsMap() ? s.begin()->first : s;
  if (std::find(stage_names.begin(), stage_names.end(), kind) == stage_names.end()) {
    const std::string near = closest(kind, stage_names);
    diag.error(Location::of(f, key), path, "unknown stage '" + kind + "'",
               (near.empty() ? "" : "did you mean '" + near + "'? ") + "stages: " + join(stage_names));
    return;
  }
  // each stage writes its own files in the run directory (and its manifest entry): once only
  if (const auto dup = std::find_if(wf.stages.begin(), wf.stages.end(), [&](const StageEntry &e) { return e.kind == kind; });
      dup != wf.stages.end()) {
    diag.error(Location::of(f, key), path, "the stage '" + kind + "' appears twice",
               "first at " + dup->where.str() + "; a workflow runs each stage once");
    return;
  }
  if (config && !config.IsNull() && !config.IsMap()) {
    diag.error(Location::of(f, config), path + "." + kind, "expected a mapping of settings");
    return;
  }
  wf.stages.push_back({kind, config && config.IsMap() ? config : YAML::Node(YAML::NodeType::Map), Location::of(f, s)});
}

void read_stages(Workflow &wf, const std::vector<std::string> &stage_names, const std::string &f, Diagnostics &diag) {
  const YAML::Node stages = wf.root["stages"];
  if (!stages)
    diag.error(Location::of(f, wf.root), "stages", "missing",
               "add a list, e.g. stages: [{simulate: {...}}, {characterise: {...}}]");
  else if (!stages.IsSequence())
    diag.error(Location::of(f, stages), "stages", "expected a list of stages (- simulate: {...})");
  else
    for (std::size_t i = 0; i < stages.size(); ++i) read_stage(wf, stages[i], i, stage_names, f, diag);
}

}  // namespace

Workflow load_workflow(const fs::path &file, const std::vector<std::string> &stage_names) {
  Workflow wf;
  wf.file = file;
  wf.dir = file.has_parent_path() ? file.parent_path() : fs::path(".");
  if (std::error_code ec; fs::is_directory(file, ec))
    throw InputError(file.string() + " is a directory; give a workflow .yaml file");
  wf.root = load_yaml(file);
  const std::string f = file.string();
  Diagnostics diag;
  if (!wf.root.IsMap()) {
    diag.error(Location::of(f, wf.root), "", "a workflow is a YAML mapping with version, name, scene and stages");
    diag.throw_if_any();
  }
  check_top_keys(wf, f, diag);
  wf.name = read_name(wf, file, diag);
  read_scene(wf, f, diag);
  read_stages(wf, stage_names, f, diag);
  diag.throw_if_any();
  return wf;
}

}  // namespace spreadmap
