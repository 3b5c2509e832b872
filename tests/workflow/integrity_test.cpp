// Nothing lost, nothing stale, nothing crashes (issue 37), through the real binary: one writer per
// run directory (the flock on <run>/.lock); a model whose predictions are NaN or infinite is refused
// by query, map and the map stage, which write nothing; numeric options read as their types, error
// lists capped, and --out or a workflow that cannot be what they must be named with the fix; a disk
// that fills up leaves no short output under its final name.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/file.h>
#include <sys/mount.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <regex>

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

// A GP trained by `spreadmap train` on a smooth 5 x 5 table of (U, omega) -> (vs, rq): <dir>/gp/model.json.
fs::path trained_gp(const fs::path &dir) {
  fs::create_directories(dir);
  {
    std::ofstream csv(dir / "data.csv");
    csv.precision(17);
    csv << "case,U,omega,vs,rq\n";
    for (int i = 0; i < 5; ++i)
      for (int k = 0; k < 5; ++k) {
        const double u = 0.04 + 0.015 * i, w = -20 + 10.0 * k;
        csv << "c" << i * 5 + k << "," << u << "," << w << "," << u * 250e-6 * (1 + 0.1 * std::tanh(w / 15)) << ","
            << 100e-6 * (1 + 0.05 * std::sin(w / 7) + 0.3 * u) << "\n";
      }
  }
  const auto r = cli({"train", (dir / "data.csv").string(), "--inputs", "U,omega", "--model", "gp", "--out",
                            (dir / "gp").string(), "--no-figures"});
  EXPECT_EQ(r.exit_code, 0) << r.describe();
  return dir / "gp" / "model.json";
}

// The model with a signal variance of e^(1e308): a valid file whose every prediction is NaN.
void damage(const fs::path &model) {
  auto j = t::json_file(model);
  j["state"]["theta"][0][0] = 1e308;
  std::ofstream(model) << j.dump(1);
}

void expect_refused_model(const t::Outcome &r, const fs::path &model) {
  ASSERT_TRUE(r.exited) << r.describe();
  EXPECT_EQ(r.exit_code, 2) << r.describe();
  EXPECT_EQ(t::crash_marker(r.err), "") << r.describe();
  EXPECT_TRUE(t::contains(r.err, "error: " + model.string() + ": the model's prediction of vs is not a finite number"))
      << r.err;
  EXPECT_TRUE(t::contains(r.err, "train it again")) << r.err;
  EXPECT_FALSE(std::regex_search(r.out, std::regex("nan|inf", std::regex::icase))) << r.out;
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

TEST(Integrity, AModelPredictingNaNIsRefusedByQueryMapAndTheMapStage) {
  const fs::path dir = t::fresh_run_directory("spreadmap_nan_model");
  const fs::path model = trained_gp(dir);
  ASSERT_TRUE(fs::exists(model));
  const fs::path run = dir / "run";
  fs::create_directories(run / "train/gp");
  fs::copy_file(model, run / "train/gp/model.json");
  {
    // reading a model does not wait for the run that holds its directory
    HeldLock writer(run, LOCK_EX, "node17 4242");
    const auto good = cli({"query", (run / "train/gp/model.json").string(), "--at", "U=70mm/s,omega=0rad/s"});
    EXPECT_EQ(good.exit_code, 0) << good.describe();
    EXPECT_TRUE(t::contains(good.out, "vs")) << good.out;
  }
  damage(model);
  damage(run / "train/gp/model.json");
  expect_refused_model(cli({"query", model.string(), "--at", "U=70mm/s,omega=0rad/s"}), model);
  expect_refused_model(cli({"query", model.string(), "--best", "--rq-max", "110um"}), model);
  expect_refused_model(cli({"map", model.string(), "--grid", "11x11", "--out", (dir / "map").string(),
                                  "--no-figures"}),
                       model);
  EXPECT_FALSE(fs::exists(dir / "map/map.csv"));
  EXPECT_FALSE(fs::exists(dir / "map/optimum.json"));
  const fs::path workflow = fs::path(SPREADMAP_SOURCE_DIR) / "tests/workflow/data/integrity/map_only.yaml";
  expect_refused_model(cli({"run", workflow.string(), "--out", run.string(), "--only", "map"}),
                       run / "train/gp/model.json");
  EXPECT_FALSE(fs::exists(run / "map/map.csv"));
  EXPECT_FALSE(fs::exists(run / "map/optimum.json"));
  if (!::testing::Test::HasFailure()) fs::remove_all(dir);
}

TEST(Integrity, NegativeNumbersAreNotReadAsHugeOnes) {
  const fs::path run = t::fresh_run_directory("spreadmap_case_minus_one");
  const auto r = cli({"run", one_case.string(), "--out", run.string(), "--case", "-1"});
  EXPECT_EQ(r.exit_code, 2) << r.describe();
  EXPECT_TRUE(t::contains(r.err, "error: --case -1: not a case number; cases are numbered from 0 (case 7 is c007)"))
      << r.err;
  EXPECT_FALSE(t::contains(r.err + r.out, "18446744073709551615")) << r.err;
  EXPECT_FALSE(fs::exists(run)) << "refused before the run directory";
  for (const char *bad : {"x", "1.5", "", "99999999999999999999999"}) {
    const auto b = cli({"run", one_case.string(), "--out", run.string(), "--case", bad});
    EXPECT_EQ(b.exit_code, 2) << b.describe();
    EXPECT_TRUE(t::contains(b.err, std::string("error: --case ") + bad + ": not a case number")) << b.err;
  }
  const auto beyond = cli({"run", one_case.string(), "--out", run.string(), "--case", "5"});
  EXPECT_EQ(beyond.exit_code, 2) << beyond.describe();
  EXPECT_TRUE(t::contains(beyond.err, "error: --case 5: the design has 1 cases, numbered 0 to 0")) << beyond.err;
  const auto folds = cli({"train", "x.csv", "--inputs", "U", "--folds", "-2"});
  EXPECT_EQ(folds.exit_code, 2) << folds.describe();
  EXPECT_TRUE(t::contains(folds.err, "error: --folds -2: not a number of folds")) << folds.err;
  fs::remove_all(run);
}

TEST(Integrity, TenThousandErrorsPrintFiftyAndTheCount) {
  const fs::path dir = t::fresh_run_directory("spreadmap_many_errors");
  fs::create_directories(dir);
  {
    std::ofstream wf(dir / "many.yaml");
    wf << t::slurp(one_case);
    for (int i = 0; i < 10000; ++i) wf << "unknown_key_" << i << ": 1\n";
  }
  for (const std::string command : {"validate", "run"}) {
    std::vector<std::string> args = {command, (dir / "many.yaml").string()};
    if (command == "run") args.insert(args.end(), {"--out", (dir / "run").string()});
    const auto r = cli(args);
    EXPECT_EQ(r.exit_code, 2) << r.describe();
    EXPECT_LT(r.err.size(), 20000u) << command;
    const std::string tail = "... and 9950 more errors (fix these and run again to see them)\n";
    ASSERT_GE(r.err.size(), tail.size()) << r.err;
    EXPECT_EQ(r.err.substr(r.err.size() - tail.size()), tail) << command;
    EXPECT_TRUE(t::contains(r.err, ": unknown_key_49: unknown key")) << r.err.substr(0, 2000);
    EXPECT_FALSE(t::contains(r.err, "unknown_key_50:")) << command;
  }
  fs::remove_all(dir);
}

TEST(Integrity, AnOutThatCannotBeAFolderIsNamedWithTheFix) {
  const fs::path dir = t::fresh_run_directory("spreadmap_bad_out");
  fs::create_directories(dir);
  std::ofstream(dir / "a_file") << "not a folder\n";
  const auto file = cli({"run", one_case.string(), "--out", (dir / "a_file").string()});
  EXPECT_EQ(file.exit_code, 2) << file.describe();
  EXPECT_TRUE(t::contains(file.err, "error: --out " + (dir / "a_file").string() +
                                        ": is a file, not a folder; give a new folder or an earlier run's directory"))
      << file.err;
  EXPECT_EQ(t::slurp(dir / "a_file"), "not a folder\n");
  const auto below = cli({"run", one_case.string(), "--out", (dir / "a_file/run").string()});
  EXPECT_EQ(below.exit_code, 2) << below.describe();
  EXPECT_TRUE(t::contains(below.err, "error: --out " + (dir / "a_file/run").string() +
                                         ": cannot create the folder (Not a directory); give a folder in a place "
                                         "you can write to"))
      << below.err;
  for (const auto *r : {&file, &below}) EXPECT_FALSE(t::contains(r->err, "filesystem error")) << r->err;
  fs::remove_all(dir);
}

TEST(Integrity, AFolderGivenAsTheWorkflowIsNamed) {
  const fs::path dir = t::fresh_run_directory("spreadmap_folder_workflow");
  fs::create_directories(dir);
  const auto r = cli({"run", dir.string(), "--out", (dir / "run").string()});
  EXPECT_EQ(r.exit_code, 2) << r.describe();
  EXPECT_TRUE(t::contains(r.err, "error: " + dir.string() + " is a directory; give a workflow .yaml file")) << r.err;
  const auto v = cli({"validate", dir.string()});
  EXPECT_EQ(v.exit_code, 2) << v.describe();
  EXPECT_TRUE(t::contains(v.err, "error: " + dir.string() + " is a directory; give a file")) << v.err;
  fs::remove_all(dir);
}

// A manifest that is valid JSON of another shape (a list of cases that is text, a case without id)
// is refused naming the file and the fix, never a raw json.exception.type_error.
TEST(Integrity, AManifestOfTheWrongShapeIsNamedWithTheFix) {
  const fs::path dir = t::fresh_run_directory("spreadmap_manifest_shape");
  for (const auto &[manifest, problem] : std::vector<std::pair<std::string, std::string>>{
           {R"({"format": "spreadmap-run", "cases": "c000"})", "cases is not a list"},
           {R"({"cases": [{"inputs": {}}]})", "an entry of cases is not an object with a text id"},
           {R"([1, 2])", "it is not a JSON object"},
           {R"({"stages": 3})", "stages is not an object"}}) {
    fs::create_directories(dir);
    std::ofstream(dir / "manifest.json") << manifest;
    const auto r = cli({"run", one_case.string(), "--out", dir.string()});
    EXPECT_EQ(r.exit_code, 1) << r.describe();
    EXPECT_EQ(t::crash_marker(r.err), "") << r.describe();
    EXPECT_TRUE(t::contains(r.err, "error: " + (dir / "manifest.json").string() + ": not a spreadmap run manifest (" +
                                       problem + "): move it away"))
        << r.err;
    EXPECT_FALSE(t::contains(r.err, "type_error")) << r.err;
  }
  fs::remove_all(dir);
}

// `spreadmap simulate` onto a disk that fills up in the first particles CSV: exit 1 naming the file
// and the fix, and no short file under its final name. The tmpfs holds the scene, the first .vtp and
// the whole pages of the CSV but not its last partial page. (The CSV was an ofstream checked before
// its final flush: here it said only "error: write failed"; a failure in that flush went unseen and
// left a short file.) Needs root to mount the tmpfs, as the test command runs.
TEST(Integrity, AFullDiskLeavesNoShortOutput) {
  const fs::path dir = t::fresh_run_directory("spreadmap_full_disk");
  fs::create_directories(dir / "full");
  {
    std::ofstream csv(dir / "grid.csv");
    csv << "x,y,z,vx,vy,vz,wx,wy,wz,radius,density\n";
    for (int i = 0; i < 400; ++i)
      csv << 0.3e-3 * (i % 20) << "," << 0.3e-3 * (i / 20) << ",0.001,0,0,0,0,0,0,0.0001,2500\n";
    std::ofstream(dir / "grid.yaml")
        << "version: 1\nname: grid\ndomain: {lo: [-1 mm, -1 mm, 0 mm], hi: [7 mm, 7 mm, 3 mm]}\ngravity: off\n"
           "contact: {use: hooke_slider, v_max: 1 m/s, overlap_max: 10 um, restitution: 0.7, friction: 0.3}\n"
           "particles: {file: grid.csv}\nrun: {duration: 0.1 ms, output_times: [0 ms, 0.1 ms]}\n";
  }
  const auto whole = cli({"simulate", (dir / "grid.yaml").string(), "--out", (dir / "whole").string()});
  ASSERT_EQ(whole.exit_code, 0) << whole.describe();
  const auto pages = [&](const char *name, bool partial_page) {
    const auto size = fs::file_size(dir / "whole" / name);
    return size / 4096 + (partial_page && size % 4096 ? 1 : 0);
  };
  ASSERT_NE(fs::file_size(dir / "whole/particles_0000.csv") % 4096, 0u) << "a last partial page to refuse";
  const auto size = 4096 * (pages("scene.json", true) + pages("state_0000.vtp", true) +
                            pages("particles_0000.csv", false));
  const std::string options = "size=" + std::to_string(size);
  ASSERT_EQ(::mount("tmpfs", (dir / "full").c_str(), "tmpfs", 0, options.c_str()), 0)
      << "cannot mount a small tmpfs (" << std::strerror(errno) << "): this test needs root, as the test command has";
  const auto full = cli({"simulate", (dir / "grid.yaml").string(), "--out", (dir / "full").string()});
  EXPECT_EQ(full.exit_code, 1) << full.describe();
  EXPECT_TRUE(t::contains(full.err, "error: cannot write " + (dir / "full/particles_0000.csv").string())) << full.err;
  EXPECT_TRUE(t::contains(full.err, "free some disk space")) << full.err;
  EXPECT_FALSE(fs::exists(dir / "full/particles_0000.csv")) << fs::file_size(dir / "full/particles_0000.csv");
  EXPECT_EQ(t::slurp(dir / "full/state_0000.vtp"), t::slurp(dir / "whole/state_0000.vtp"));
  for (const auto &e : fs::directory_iterator(dir / "full"))
    EXPECT_EQ(e.path().filename().string().find(".tmp-"), std::string::npos) << "a temporary is left: " << e.path();
  ::umount2((dir / "full").c_str(), MNT_DETACH);
  fs::remove_all(dir);
}
