// One run directory, one writer: an advisory lock (flock) on <run>/.lock, held by every command that
// writes into the directory until it exits. The file names the holder's host and pid, so a refused
// command can say who holds it. The kernel frees a flock when its holder dies, so the lock of a
// crashed or killed run is simply taken over; nothing stale needs removing by hand.
#pragma once
#include <filesystem>

namespace spreadmap {

class RunLock {
 public:
  // exclusive: a whole run (manifest, cases, stages). shared: one case of a Slurm array
  // (`run --case N`), which leaves manifest.json alone, so such tasks may hold it together.
  enum class Mode { exclusive, shared };
  // Creates the folder if needed and takes its lock at once, or throws naming the directory and
  // the fix: InputError when it cannot be a folder (--out names a file, an unwritable place),
  // RunFailure when another command holds the lock (with that command's host and pid).
  RunLock(const std::filesystem::path &dir, Mode mode);
  ~RunLock();
  RunLock(const RunLock &) = delete;
  RunLock &operator=(const RunLock &) = delete;

 private:
  int fd_ = -1;
};

}  // namespace spreadmap
