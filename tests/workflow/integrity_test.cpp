// Nothing lost, nothing stale, nothing crashes (issue 37), through the real binary: one writer per
// run directory (the flock on <run>/.lock).
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/file.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fstream>

#include "workflow/process.hpp"
#include "workflow/run_files.hpp"

namespace fs = std::filesystem;
namespace t = spreadmap::test;

namespace {

const fs::path one_case = fs::path(SPREADMAP_SOURCE_DIR) / "tests/workflow/data/integrity/one_case.yaml";

t::Outcome cli(std::vector<std::string> args) { return t::run({std::move(args), {}, {}, {}}); }

// Another writer, as this test process: flock on <dir>/.lock naming `host` and `pid`.
class HeldLock {
 public:
  HeldLock(const fs::path &dir, int op, const std::string &holder) {
    fs::create_directories(dir);
    std::ofstream(dir / ".lock") << holder << "\n";
    fd_ = ::open((dir / ".lock").c_str(), O_RDWR | O_CLOEXEC);
    EXPECT_EQ(::flock(fd_, op | LOCK_NB), 0);
  }
  ~HeldLock() { release(); }
  void release() {
    if (fd_ >= 0) ::close(fd_);
    fd_ = -1;
  }

 private:
  int fd_ = -1;
};

// The pid of a process that has just exited.
pid_t exited_pid() {
  const pid_t child = ::fork();
  if (child == 0) ::_exit(0);
  ::waitpid(child, nullptr, 0);
  return child;
}

std::string hostname() {
  char name[256] = {};
  ::gethostname(name, sizeof name - 1);
  return name;
}

}  // namespace

TEST(Integrity, ASecondWriterIsRefusedNamingTheHolderAndTheFix) {
  const fs::path run = t::fresh_run_directory("spreadmap_lock");
  HeldLock held(run, LOCK_EX, "node17 4242");
  const auto refused = cli({"run", one_case.string(), "--out", run.string()});
  ASSERT_TRUE(refused.exited) << refused.describe();
  EXPECT_EQ(refused.exit_code, 1) << refused.describe();
  EXPECT_TRUE(t::contains(refused.err, "error: " + run.string() + ": spreadmap pid 4242 on host node17 is writing "
                                       "into this run directory; wait for it to finish, or give this run another "
                                       "--out"))
      << refused.err;
  EXPECT_FALSE(fs::exists(run / "cases")) << "a refused run touched the cases";
  EXPECT_FALSE(fs::exists(run / "manifest.json"));
  // one case of a Slurm array shares the directory with its siblings, never with a whole run
  const auto one = cli({"run", one_case.string(), "--out", run.string(), "--case", "0"});
  EXPECT_NE(one.exit_code, 0) << one.describe();
  EXPECT_TRUE(t::contains(one.err, "pid 4242 on host node17")) << one.err;
  EXPECT_FALSE(fs::exists(run / "cases"));

  held.release();
  const auto ran = cli({"run", one_case.string(), "--out", run.string()});
  ASSERT_EQ(ran.exit_code, 0) << ran.describe();
  EXPECT_TRUE(fs::exists(run / "cases/c000"));
  // the lock names its last holder, and is free again once it has exited
  EXPECT_TRUE(t::contains(t::slurp(run / ".lock"), hostname() + " ")) << t::slurp(run / ".lock");
  HeldLock after(run, LOCK_EX, "node17 4242");
  fs::remove_all(run);
}

TEST(Integrity, CasesOfOneArrayShareTheLock) {
  const fs::path run = t::fresh_run_directory("spreadmap_lock_shared");
  HeldLock sibling(run, LOCK_SH, "node3 77");
  const auto one = cli({"run", one_case.string(), "--out", run.string(), "--case", "0"});
  ASSERT_EQ(one.exit_code, 0) << one.describe();
  EXPECT_TRUE(fs::exists(run / "cases/c000"));
  const auto whole = cli({"run", one_case.string(), "--out", run.string()});
  EXPECT_EQ(whole.exit_code, 1) << whole.describe();
  sibling.release();
  fs::remove_all(run);
}

TEST(Integrity, TheLockOfAnExitedRunIsTakenOver) {
  const fs::path run = t::fresh_run_directory("spreadmap_lock_stale");
  const pid_t dead = exited_pid();
  fs::create_directories(run);
  std::ofstream(run / ".lock") << hostname() << " " << dead << "\n";
  const auto ran = cli({"run", one_case.string(), "--out", run.string()});
  ASSERT_EQ(ran.exit_code, 0) << ran.describe();
  EXPECT_TRUE(t::contains(ran.err, "taking over the lock of pid " + std::to_string(dead) + ", which has exited"))
      << ran.err;
  fs::remove_all(run);
}
