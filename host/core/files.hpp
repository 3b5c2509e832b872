// Every file the host writes (outputs, the manifest, checkpoints, metrics, figures, models) goes
// through write_atomic_with: the content goes to a temporary beside the target, reaches the disk
// (fsync) and is renamed over the target, so a reader or a crash sees the old file or the new one,
// never half of one.
#pragma once
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <string_view>

namespace spreadmap {

namespace fs = std::filesystem;

// `write` gets the temporary path (an empty file, already created) and fills it, by name, as
// libraries that write files themselves do (VTK, gl2ps). Then the temporary is synced to disk and
// renamed over `path`; missing folders are created, the folder is synced after the rename. On any
// failure the temporary is removed and `path` keeps its previous content: an exception thrown by
// `write` passes through unchanged, the writer's own failures are RunFailure naming `path` and the
// fix. May be called from any thread, also for the same `path`: the last rename wins.
void write_atomic_with(const fs::path &path, const std::function<void(const fs::path &tmp)> &write);
// write_atomic_with for content held in memory.
void write_atomic(const fs::path &path, std::string_view content);
// The temporary's name for `path`: hidden, in the same folder (rename needs the same file system),
// ".<name>.tmp-<pid>-<count>-<random><extension>", so writers that pick a format by extension still
// work. Unique per process and call; the random part separates hosts sharing a folder, and
// write_atomic_with creates it exclusively, so two writers are never handed the same file.
fs::path temporary_beside(const fs::path &path);

// Removes, under `folder`, the temporaries of writes that never finished (their writer was killed):
// those whose writer no longer runs here and that are over a minute old. Returns how many.
std::size_t remove_stale_temporaries(const fs::path &folder);

std::string read_text(const fs::path &path);  // throws InputError naming the file
// 64-bit FNV-1a-style hash as 16 hex digits: stable across machines and versions (input hashes in the
// manifest, heap file names). Its offset basis is 1469598103934665603, not FNV's 14695981039346656037:
// keep it, since changing it would make every existing run directory recompute its cases.
std::string stable_hash(const std::string &text);

}  // namespace spreadmap
