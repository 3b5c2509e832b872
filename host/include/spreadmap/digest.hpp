// A file's content digest: 64-bit FNV-1a of its bytes as 16 hex digits. The host keys cached results
// on it (a changed input is a different case) and a plugin that reads a file checks it against the
// digest the host took when it validated the input.
#pragma once
#include <cstdint>
#include <cstdio>
#include <string>
#include <string_view>

namespace spreadmap {

inline std::string content_digest(std::string_view bytes) {
  std::uint64_t h = 1469598103934665603ull;
  for (unsigned char c : bytes) h = (h ^ c) * 1099511628211ull;
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(h));
  return text;
}

}  // namespace spreadmap
