// Plugins by kind and name, loaded with Boost.DLL. Search order: every folder of
// SPREADMAP_PLUGIN_PATH (colon-separated), then ../lib/spreadmap/plugins beside the binary; in each
// folder <kind>/<name>.so, then <name>.so. The first match wins; a shadowed duplicate is logged once.
// Libraries stay loaded until exit. Never a path from a workflow file: plugins are chosen by name.
#pragma once
#include <spreadmap/abi.h>

#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace boost::dll {
class shared_library;
}

namespace spreadmap {

namespace fs = std::filesystem;

inline const std::vector<std::string> &plugin_kinds() {
  static const std::vector<std::string> kinds = {"contact", "spreader", "metrics", "surrogate"};
  return kinds;
}

struct LoadedPlugin {
  const sm_plugin_v1 *descriptor = nullptr;
  fs::path file;
  std::string id() const;  // "kind/name"
};

class PluginRegistry {
 public:
  explicit PluginRegistry(std::vector<fs::path> roots);
  ~PluginRegistry();
  // SPREADMAP_PLUGIN_PATH entries, then <dir of the running binary>/../lib/spreadmap/plugins.
  static std::vector<fs::path> default_roots();
  // The process-wide registry over default_roots().
  static PluginRegistry &global();

  // Loads kind/name or throws PluginError (unknown name with suggestions, ABI mismatch, missing entry
  // point, kind or name that does not match the file).
  const LoadedPlugin &get(const std::string &kind, const std::string &name);
  // Loads one library file directly (tests, diagnostics). Same checks as get().
  const LoadedPlugin &load_file(const fs::path &file, const std::string &expected_kind = "");
  // Names available for a kind (files found, not yet loaded).
  std::vector<std::string> names(const std::string &kind) const;
  const std::vector<fs::path> &roots() const { return roots_; }

 private:
  std::vector<fs::path> candidates(const std::string &kind, const std::string &name) const;
  std::vector<fs::path> roots_;
  std::vector<std::shared_ptr<boost::dll::shared_library>> libraries_;
  std::map<std::string, LoadedPlugin> loaded_;  // by file path and by kind/name
};

// An instance made by a plugin's create(), freed by the same plugin's destroy().
class PluginInstance {
 public:
  PluginInstance() = default;
  // Throws PluginError "kind/name: <plugin's text>" when create() refuses.
  PluginInstance(const LoadedPlugin &plugin, const std::string &params_json, const std::string &where = "");
  PluginInstance(PluginInstance &&o) noexcept : plugin_(o.plugin_), self_(o.self_) { o.self_ = nullptr; }
  PluginInstance &operator=(PluginInstance &&o) noexcept;
  PluginInstance(const PluginInstance &) = delete;
  PluginInstance &operator=(const PluginInstance &) = delete;
  ~PluginInstance();
  void *get() const { return self_; }
  const LoadedPlugin *plugin() const { return plugin_; }
  template <class Ops> const Ops *ops() const { return static_cast<const Ops *>(plugin_->descriptor->ops); }

 private:
  const LoadedPlugin *plugin_ = nullptr;
  void *self_ = nullptr;
};

}  // namespace spreadmap
