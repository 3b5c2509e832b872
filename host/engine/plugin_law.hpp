// A contact law from a contact plugin, for programs that build a scene in code (docs/engine.md):
//
//   const auto law = spreadmap::engine::load_contact_law("hooke_slider", {{"restitution", 0.5}});
//   spreadmap::engine::Simulation<> sim(domain, law.law());
//
// Parameters are the plugin's schema keys (`spreadmap plugins NAME` lists them), validated as in a
// workflow: bare numbers are SI, a string may carry a unit ("2.5 um"), missing keys take their
// defaults, and a bad value throws InputError naming the key and the fix.
//
// Plugins are found by name in `plugin_dirs`, each searched as <dir>/contact/<name>.so, then
// <dir>/<name>.so. By default: every folder of SPREADMAP_PLUGIN_PATH, the folder beside the running
// program (../lib/spreadmap/plugins), then the plugin folder of the spreadmap package the program was
// compiled against (the CMake target spreadmap::engine defines SPREADMAP_PACKAGE_PLUGIN_DIR).
#pragma once
#include <core/error.hpp>  // InputError, PluginError
#include <core/registry.hpp>
#include <engine/walls.hpp>

#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#ifndef SPREADMAP_PACKAGE_PLUGIN_DIR
#define SPREADMAP_PACKAGE_PLUGIN_DIR ""
#endif

namespace spreadmap::engine {

// Owns one bound instance of a contact plugin and keeps the plugin's library loaded. Move-only.
// It must outlive every Simulation and wall given its law(). Stepping only reads the instance, so one
// PluginLaw may serve several Simulations, also on different threads.
class PluginLaw {
 public:
  PluginLaw(std::shared_ptr<PluginRegistry> registry, PluginInstance instance, nlohmann::json params);
  // What Simulation and the walls take: a view valid while this object lives (also after a move).
  ContactLaw law() const;
  std::string id() const;                                   // "contact/<name>"
  const nlohmann::json &params() const { return params_; }  // every schema key, numbers in SI
  const std::filesystem::path &file() const;                // the library it came from

 private:
  std::shared_ptr<PluginRegistry> registry_;  // holds the library; outlives instance_ (declared first)
  PluginInstance instance_;
  nlohmann::json params_;
};

// The law the engine takes from a bound contact-plugin instance (its ABI minor version included).
ContactLaw bound_law(const PluginInstance &instance);

// The default search folders (above). `package_dir` empty: none from a package.
std::vector<std::filesystem::path> plugin_search_path(
    const std::filesystem::path &package_dir = SPREADMAP_PACKAGE_PLUGIN_DIR);

// Loads contact/<name> and binds it to `params` (a JSON object; empty or null: all defaults). Throws
// PluginError for an unknown name (with the closest names and the folders searched) or a plugin that
// refuses its parameters, InputError for a parameter that fails the schema. Thread-safe.
PluginLaw load_contact_law(const std::string &name, const nlohmann::json &params = nlohmann::json::object(),
                           const std::vector<std::filesystem::path> &plugin_dirs = plugin_search_path());

}  // namespace spreadmap::engine
