// Kill and resume: `spreadmap run` is interrupted with SIGINT once its first case has finished. It
// must stop cleanly (exit 130, a message saying how to resume, no half-written file anywhere); the
// same command then runs only the unfinished cases — the finished ones keep their files untouched
// (same inode and modification time: write_atomic would have replaced the inode) and their manifest
// timings — and a third run recomputes nothing at all.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <thread>

#include "workflow/process.hpp"

namespace fs = std::filesystem;
namespace t = spreadmap::test;

namespace {

constexpr int n_cases = 4;

std::string case_id(int i) {
  char buf[8];
  std::snprintf(buf, sizeof buf, "c%03d", i);
  return buf;
}

std::string slurp(const fs::path &p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// What identifies one written file: a rewrite (temporary + rename) changes the inode.
struct FileId {
  ino_t inode = 0;
  std::int64_t mtime_ns = 0;
  std::string content;
  bool operator==(const FileId &) const = default;
};

void PrintTo(const FileId &f, std::ostream *os) {
  *os << "{inode " << f.inode << ", mtime " << f.mtime_ns << " ns, " << f.content.size() << " bytes}";
}

FileId identify(const fs::path &p) {
  struct stat st {};
  if (::stat(p.c_str(), &st) != 0) return {};
  return {st.st_ino, std::int64_t(st.st_mtim.tv_sec) * 1000000000 + st.st_mtim.tv_nsec, slurp(p)};
}

// Every regular file below `dir`, by relative path.
std::map<std::string, FileId> snapshot(const fs::path &dir) {
  std::map<std::string, FileId> out;
  for (const auto &e : fs::recursive_directory_iterator(dir))
    if (e.is_regular_file()) out[fs::relative(e.path(), dir).string()] = identify(e.path());
  return out;
}

std::vector<std::string> temporaries(const fs::path &dir) {
  std::vector<std::string> out;
  for (const auto &e : fs::recursive_directory_iterator(dir))
    if (e.path().filename().string().find(".tmp") != std::string::npos) out.push_back(e.path().string());
  return out;
}

bool finished(const fs::path &case_dir) {
  if (!fs::exists(case_dir / "case.json") || !fs::exists(case_dir / "state.vtp")) return false;
  return nlohmann::json::parse(slurp(case_dir / "case.json")).value("status", "") == "done";
}

nlohmann::json manifest_case(const fs::path &run, const std::string &id) {
  const auto manifest = nlohmann::json::parse(slurp(run / "manifest.json"));
  for (const auto &c : manifest.at("cases"))
    if (c.at("id") == id) return c;
  return nullptr;
}

bool contains(const std::string &text, const std::string &part) { return text.find(part) != std::string::npos; }

}  // namespace

TEST(KillAndResume, FinishedCasesAreNeverRecomputedAndNoPartialFileIsLeft) {
  const fs::path workflow = fs::path(SPREADMAP_SOURCE_DIR) / "tests/workflow/data/resume/tiny_resume.yaml";
  const fs::path run = fs::temp_directory_path() / ("spreadmap_resume_" + std::to_string(::getpid()));
  fs::remove_all(run);
  const t::Command command{{"run", workflow.string(), "--out", run.string()}, {}, {}, {}};

  // 1. run, and interrupt as soon as the first case is complete
  t::Outcome first;
  {
    t::Child child(command);
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::minutes(4);
    while (child.running() && !finished(run / "cases" / case_id(0)) && std::chrono::steady_clock::now() < deadline)
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    ASSERT_TRUE(child.running()) << "the run ended before it could be interrupted:\n" << child.wait().describe();
    child.signal(SIGINT);
    first = child.wait();
  }
  ASSERT_TRUE(first.exited) << first.describe();
  EXPECT_EQ(first.exit_code, 130) << first.describe();
  EXPECT_EQ(t::crash_marker(first.err), "") << first.describe();
  EXPECT_TRUE(contains(first.err, "run the same command again to resume")) << first.err;
  EXPECT_EQ(temporaries(run), std::vector<std::string>{});

  std::vector<std::string> done, todo;
  for (int i = 0; i < n_cases; ++i) (finished(run / "cases" / case_id(i)) ? done : todo).push_back(case_id(i));
  ASSERT_GE(done.size(), 1u);
  ASSERT_LT(done.size(), std::size_t(n_cases)) << "every case finished before the signal: the test proves nothing";
  for (const auto &id : todo) {
    EXPECT_FALSE(fs::exists(run / "cases" / id / "case.json")) << id;
    EXPECT_FALSE(fs::exists(run / "cases" / id / "state.vtp")) << id;
  }
  // the case that was running when the signal came kept a checkpoint (unless it had not started)
  const bool checkpointed = fs::exists(run / "cases" / todo.front() / "checkpoint.bin");

  std::map<std::string, FileId> kept;
  std::map<std::string, nlohmann::json> timings;
  for (const auto &id : done) {
    for (const char *f : {"case.json", "state.vtp", "scene.json"})
      kept[id + "/" + f] = identify(run / "cases" / id / f);
    timings[id] = manifest_case(run, id);
    EXPECT_EQ(timings[id].value("status", ""), "done") << timings[id].dump();
  }
  const auto heaps_before = snapshot(run / "heaps");

  // 2. the same command resumes: only the unfinished cases run
  const t::Outcome second = t::run(command);
  ASSERT_TRUE(second.exited) << second.describe();
  ASSERT_EQ(second.exit_code, 0) << second.describe();
  EXPECT_TRUE(contains(second.err, std::to_string(n_cases) + " cases, " + std::to_string(todo.size()) + " to run, " +
                                       std::to_string(done.size()) + " finished already"))
      << second.err;
  if (checkpointed) {
    EXPECT_TRUE(contains(second.err, todo.front() + ": resuming from its checkpoint")) << second.err;
  }
  for (const auto &[file, id] : kept) EXPECT_EQ(identify(run / "cases" / file), id) << file << " was rewritten";
  for (const auto &[id, timing] : timings) {
    const auto now = manifest_case(run, id);
    EXPECT_EQ(now.value("start", ""), timing.value("start", "")) << id;
    EXPECT_EQ(now.value("end", ""), timing.value("end", "")) << id;
  }
  EXPECT_EQ(snapshot(run / "heaps"), heaps_before) << "the settled heap was recomputed";
  for (int i = 0; i < n_cases; ++i) {
    const fs::path c = run / "cases" / case_id(i);
    EXPECT_TRUE(finished(c)) << case_id(i);
    EXPECT_FALSE(fs::exists(c / "checkpoint.bin")) << case_id(i);
    EXPECT_EQ(manifest_case(run, case_id(i)).value("status", ""), "done") << case_id(i);
  }
  EXPECT_EQ(temporaries(run), std::vector<std::string>{});

  // 3. nothing left to do: no case file changes at all
  const auto cases_before = snapshot(run / "cases");
  const t::Outcome third = t::run(command);
  ASSERT_EQ(third.exit_code, 0) << third.describe();
  EXPECT_TRUE(contains(third.err,
                       std::to_string(n_cases) + " cases, 0 to run, " + std::to_string(n_cases) + " finished already"))
      << third.err;
  EXPECT_EQ(snapshot(run / "cases"), cases_before);
  fs::remove_all(run);
}

TEST(KillAndResume, SigtermDuringTheFirstCaseStopsCleanly) {
  const fs::path workflow = fs::path(SPREADMAP_SOURCE_DIR) / "tests/workflow/data/resume/tiny_resume.yaml";
  const fs::path run = fs::temp_directory_path() / ("spreadmap_sigterm_" + std::to_string(::getpid()));
  fs::remove_all(run);
  t::Outcome r;
  {
    t::Child child({{"run", workflow.string(), "--out", run.string()}, {}, {}, {}});
    // scene.json of every case is written before the first case starts: from then on it is running
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::minutes(2);
    while (child.running() && !fs::exists(run / "cases" / case_id(n_cases - 1) / "scene.json") &&
           std::chrono::steady_clock::now() < deadline)
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    ASSERT_TRUE(child.running()) << child.wait().describe();
    child.signal(SIGTERM);
    r = child.wait();
  }
  ASSERT_TRUE(r.exited) << r.describe();
  EXPECT_EQ(r.exit_code, 130) << r.describe();
  EXPECT_EQ(t::crash_marker(r.err), "") << r.describe();
  EXPECT_TRUE(contains(r.err, "run the same command again to resume")) << r.err;
  EXPECT_EQ(temporaries(run), std::vector<std::string>{});
  EXPECT_FALSE(finished(run / "cases" / case_id(n_cases - 1)));
  fs::remove_all(run);
}

namespace {

// Two cases of the tiny workflow, U given as the text of the second.
fs::path two_case_workflow(const fs::path &dir, const std::string &second_u) {
  fs::create_directories(dir);
  const fs::path wf = dir / "wf.yaml";
  std::ofstream(wf) << "version: 1\nname: rerun\nscene:\n  preset: quick\n  threads: 1\n  domain: {length: 20 mm}\n"
                       "  powder: {count: 300, heap_from: 6 mm, heap_to: 10 mm, settle_time: 0.02 s}\n"
                       "  spreader: {use: roller, travel: 8 mm}\nstages:\n  - simulate:\n      render: false\n"
                       "      design: {type: list, cases: [{U: 100 mm/s}, {U: "
                    << second_u << "}]}\n";
  return wf;
}

}  // namespace

TEST(Rerun, OnlyWhatChangedOrWasDamagedIsRecomputedAndForceRecomputesAll) {
  const fs::path dir = fs::temp_directory_path() / ("spreadmap_rerun_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  const fs::path run = dir / "out";
  const t::Command command{{"run", two_case_workflow(dir, "90 mm/s").string(), "--out", run.string()}, {}, {}, {}};
  ASSERT_EQ(t::run(command).exit_code, 0);
  const fs::path c0 = run / "cases" / case_id(0), c1 = run / "cases" / case_id(1);
  const FileId state0 = identify(c0 / "state.vtp"), state1 = identify(c1 / "state.vtp");

  // 1. the second case's speed changes: it runs again, the first keeps its files
  two_case_workflow(dir, "80 mm/s");
  const t::Outcome changed = t::run(command);
  ASSERT_EQ(changed.exit_code, 0) << changed.describe();
  EXPECT_TRUE(contains(changed.err, "2 cases, 1 to run, 1 finished already")) << changed.err;
  EXPECT_EQ(identify(c0 / "state.vtp"), state0);
  EXPECT_NE(identify(c1 / "state.vtp"), state1);
  EXPECT_EQ(nlohmann::json::parse(slurp(c1 / "case.json"))["inputs"]["U"].get<double>(), 0.08);

  // 2. a damaged result (a state cut short, as by a node that died while copying) is recomputed
  const std::string whole = slurp(c0 / "state.vtp");
  std::ofstream(c0 / "state.vtp", std::ios::binary | std::ios::trunc) << whole.substr(0, whole.size() / 2);
  const FileId state1_now = identify(c1 / "state.vtp");
  const t::Outcome damaged = t::run(command);
  ASSERT_EQ(damaged.exit_code, 0) << damaged.describe();
  EXPECT_TRUE(contains(damaged.err, "2 cases, 1 to run, 1 finished already")) << damaged.err;
  EXPECT_EQ(slurp(c0 / "state.vtp"), whole) << "deterministic: the recomputed state is the same file";
  EXPECT_EQ(identify(c1 / "state.vtp"), state1_now);

  // 3. --force recomputes every case
  t::Command forced = command;
  forced.args.push_back("--force");
  const FileId before0 = identify(c0 / "state.vtp"), before1 = identify(c1 / "state.vtp");
  const t::Outcome all = t::run(forced);
  ASSERT_EQ(all.exit_code, 0) << all.describe();
  EXPECT_TRUE(contains(all.err, "2 cases, 2 to run, 0 finished already")) << all.err;
  EXPECT_NE(identify(c0 / "state.vtp").inode, before0.inode);
  EXPECT_NE(identify(c1 / "state.vtp").inode, before1.inode);
  fs::remove_all(dir);
}
