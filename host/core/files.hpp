// Files are written to a temporary name beside the target and renamed, so a crash or a signal never
// leaves a half-written file under the final name.
#pragma once
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>

namespace spreadmap {

namespace fs = std::filesystem;

void write_atomic(const fs::path &path, const std::string &content);
// For writers that need a path (libraries that write files themselves): `write` gets the temporary
// path; on success it is renamed to `path`, on exception removed.
void write_atomic_with(const fs::path &path, const std::function<void(const fs::path &tmp)> &write);
std::string read_text(const fs::path &path);  // throws InputError naming the file
// A temporary name beside `path`, unique per process and call.
fs::path temporary_beside(const fs::path &path);
// 64-bit FNV-1a-style hash as 16 hex digits: stable across machines and versions (input hashes in the
// manifest, heap file names). Its offset basis is 1469598103934665603, not FNV's 14695981039346656037:
// keep it, since changing it would make every existing run directory recompute its cases.
std::string stable_hash(const std::string &text);

}  // namespace spreadmap
