#include <engine/plugin_law.hpp>

#include <core/plugin_abi.hpp>

#include <algorithm>
#include <spreadmap/contact.hpp>
#include <nlohmann/json.hpp>
#include <yaml-cpp/yaml.h>

#include "core/diagnostics.hpp"
#include "core/schema.hpp"

namespace spreadmap::engine {

namespace fs = std::filesystem;

PluginLaw::PluginLaw(std::shared_ptr<PluginRegistry> registry, PluginInstance instance, nlohmann::json params)
    : registry_(std::move(registry)), instance_(std::move(instance)), params_(std::move(params)) {}

ContactLaw bound_law(const PluginInstance &instance) {
  return {instance.ops<sm_contact_ops_v1>(), instance.get(), abi_minor(*instance.plugin()->descriptor)};
}

ContactLaw PluginLaw::law() const { return bound_law(instance_); }

std::string PluginLaw::id() const { return instance_.plugin()->id(); }

const fs::path &PluginLaw::file() const { return instance_.plugin()->file; }

std::vector<fs::path> plugin_search_path(const fs::path &package_dir) {
  std::vector<fs::path> dirs = PluginRegistry::default_roots();
  // The same folder twice would make the registry report a plugin as shadowing itself.
  const auto same = [&](const fs::path &dir) {
    std::error_code ec;
    return fs::equivalent(dir, package_dir, ec);
  };
  if (!package_dir.empty() && std::none_of(dirs.begin(), dirs.end(), same)) dirs.push_back(package_dir);
  return dirs;
}

PluginLaw load_contact_law(const std::string &name, const nlohmann::json &params,
                           const std::vector<fs::path> &plugin_dirs) {
  // A registry of its own: nothing shared between calls (thread-safe), and the law keeps it.
  auto registry = std::make_shared<PluginRegistry>(plugin_dirs);
  const LoadedPlugin &plugin = registry->get("contact", name);
  const std::string source = "load_contact_law(\"" + name + "\")";
  Diagnostics diag;
  nlohmann::json values;
  if (!params.is_object() && !params.is_null())
    diag.error(
        Location{source}, "params", "expected a JSON object of parameters, found " + params.dump(),
        "pass {{\"restitution\", 0.5}, ...}, or {} for the defaults; `spreadmap plugins " + name + "` lists the keys");
  else values = validate_params(SchemaView::of(*plugin.descriptor), json_to_yaml(params), source, "params", diag);
  diag.throw_if_any();
  PluginInstance instance(plugin, values.dump(), source);
  return PluginLaw(std::move(registry), std::move(instance), std::move(values));
}

}  // namespace spreadmap::engine
