// Plugin ABI versions (spreadmap/abi.h): how they read, and which ones this host loads. A plugin of
// this host's major version loads when its minor is not newer than the host's; its tables then have
// the fields of its minor, and the host reads no others.
#pragma once
#include <spreadmap/abi.h>

#include <cstdint>
#include <string>

namespace spreadmap {

inline std::uint32_t abi_major(std::uint32_t abi) { return abi >> 16; }  // 0: a single count (ABI 9 and older)
inline std::uint32_t abi_minor(std::uint32_t abi) { return abi & 0xffffu; }
inline std::uint32_t abi_minor(const sm_plugin_v1 &d) { return abi_minor(d.abi); }

// "10.1"; the single counts before 10 as they were ("9").
inline std::string abi_text(std::uint32_t abi) {
  if (abi_major(abi) == 0) return std::to_string(abi);
  return std::to_string(abi_major(abi)) + "." + std::to_string(abi_minor(abi));
}

// The newest version this host loads.
inline std::string host_abi_text() {
  return abi_text(SPREADMAP_ABI_VERSION(SPREADMAP_PLUGIN_ABI_MAJOR, SPREADMAP_PLUGIN_ABI_MINOR));
}

// Empty when this host loads a plugin built for `abi`; otherwise why not, naming both versions, and the fix.
inline std::string abi_refusal(std::uint32_t abi) {
  const std::string major = std::to_string(SPREADMAP_PLUGIN_ABI_MAJOR);
  if (abi_major(abi) != SPREADMAP_PLUGIN_ABI_MAJOR)
    return "uses plugin ABI " + abi_text(abi) + ", this host loads ABI " + major + ".0 to " + host_abi_text() +
           ": rebuild it with this SDK";
  if (abi_minor(abi) > SPREADMAP_PLUGIN_ABI_MINOR)
    return "uses plugin ABI " + abi_text(abi) + ", newer than this host's " + host_abi_text() +
           ": update spreadmap, or build the plugin with -DSPREADMAP_TARGET_ABI_MINOR=" +
           std::to_string(SPREADMAP_PLUGIN_ABI_MINOR);
  return "";
}

}  // namespace spreadmap
