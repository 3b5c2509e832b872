// A preloaded shim for the kill-at-every-rename test (kill_test.cpp): counts the process's rename()
// calls and, when SPREADMAP_KILL_AT_RENAME=N is set, kills the process with SIGKILL just before its
// N-th rename, as a power cut or the OOM killer would, with the temporary written and synced but not
// yet in place. SPREADMAP_COUNT_RENAMES=FILE writes the count to FILE at exit.
#include <dlfcn.h>
#include <signal.h>

#include <atomic>
#include <cstdio>
#include <cstdlib>

namespace {
std::atomic<long> renames{0};

struct CountAtExit {
  ~CountAtExit() {
    if (const char *file = std::getenv("SPREADMAP_COUNT_RENAMES"))
      if (FILE *f = std::fopen(file, "w")) std::fprintf(f, "%ld\n", renames.load()), std::fclose(f);
  }
} count_at_exit;

void before_rename() {
  const long n = ++renames;
  static const long kill_at = [] {
    const char *v = std::getenv("SPREADMAP_KILL_AT_RENAME");
    return v ? std::atol(v) : 0L;
  }();
  if (n == kill_at) ::raise(SIGKILL);
}
}  // namespace

extern "C" int rename(const char *from, const char *to) {
  before_rename();
  static const auto real = reinterpret_cast<int (*)(const char *, const char *)>(::dlsym(RTLD_NEXT, "rename"));
  return real(from, to);
}

extern "C" int renameat(int from_dir, const char *from, int to_dir, const char *to) {
  before_rename();
  static const auto real =
      reinterpret_cast<int (*)(int, const char *, int, const char *)>(::dlsym(RTLD_NEXT, "renameat"));
  return real(from_dir, from, to_dir, to);
}
