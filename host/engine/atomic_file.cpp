#include <engine/atomic_file.hpp>
#include <engine/errors.hpp>

#include <cerrno>
#include <cstring>
#include <fmt/format.h>
#include <fstream>

namespace spreadmap::engine {

void write_file_atomic(const std::filesystem::path &path, std::string_view content) {
  std::filesystem::path tmp = path;
  tmp += ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out)
      throw SetupError(fmt::format("{}: cannot open for writing ({}); check that the folder exists and is writable",
                                   tmp.string(), std::strerror(errno)));
    out.write(content.data(), static_cast<std::streamsize>(content.size()));
    out.flush();
    if (!out) {
      std::error_code ignored;
      std::filesystem::remove(tmp, ignored);
      throw SetupError(fmt::format("{}: write failed (disk full?)", tmp.string()));
    }
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) {
    std::error_code ignored;
    std::filesystem::remove(tmp, ignored);
    throw SetupError(fmt::format("{}: cannot rename {} into place: {}", path.string(), tmp.string(), ec.message()));
  }
}

}  // namespace spreadmap::engine
