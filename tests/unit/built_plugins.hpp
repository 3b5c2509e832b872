// The plugins of this build tree (build/lib/spreadmap/plugins), for the unit tests that load real ones.
#pragma once
#include <filesystem>

#include "core/registry.hpp"

inline spreadmap::PluginRegistry &built_plugins() {
  static spreadmap::PluginRegistry r({std::filesystem::path(SPREADMAP_BINARY_DIR) / "lib" / "spreadmap" / "plugins"});
  return r;
}
