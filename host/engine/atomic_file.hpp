// Writes a file under a temporary name (path + ".tmp") and renames it into place, so a reader never
// sees half a file and a crash leaves the previous version intact.
#pragma once
#include <filesystem>
#include <string_view>

namespace spreadmap::engine {

// Throws SetupError naming the file when it cannot be written.
void write_file_atomic(const std::filesystem::path &path, std::string_view content);

}  // namespace spreadmap::engine
