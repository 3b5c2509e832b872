// A rank killed midway (SIGKILL: a node lost): mpirun ends the job; the same command then finishes
// the run, computing only the cases that had no finished result. A finished case keeps its files
// untouched (same inode and modification time: a rewrite goes through a new file) and its manifest
// timings, and every case is present exactly once.
#include <gtest/gtest.h>

#include <chrono>
#include <csignal>
#include <iostream>
#include <map>
#include <set>
#include <sstream>
#include <thread>

#include "cluster/cluster_support.hpp"

namespace fs = std::filesystem;
namespace t = spreadmap::test;

namespace {

// The processes descending from `root` (its children, theirs, ...), read from /proc's children
// lists: a few files, where scanning all of /proc takes seconds on a host with many processes.
std::vector<pid_t> descendants(pid_t root) {
  std::vector<pid_t> found, frontier{root};
  while (!frontier.empty()) {
    const pid_t p = frontier.back();
    frontier.pop_back();
    std::error_code ec;
    for (const auto &task : fs::directory_iterator(fs::path("/proc") / std::to_string(p) / "task", ec)) {
      std::istringstream children(t::slurp(task.path() / "children"));
      for (pid_t c; children >> c;) {
        found.push_back(c);
        frontier.push_back(c);
      }
    }
  }
  return found;
}

// Every process whose command line names `out`: where a kernel keeps no children lists.
std::vector<pid_t> naming(const fs::path &out) {
  std::vector<pid_t> found;
  for (const auto &e : fs::directory_iterator("/proc")) {
    const std::string name = e.path().filename().string();
    if (name.find_first_not_of("0123456789") != std::string::npos) continue;
    if (t::slurp(e.path() / "cmdline").find(out.string()) != std::string::npos) found.push_back(std::stoi(name));
  }
  return found;
}

// The pid of MPI rank `rank` among the processes mpirun (`job`, writing to `out`) started, or -1.
pid_t rank_pid(int rank, pid_t job, const fs::path &out) {
  const std::string want = "OMPI_COMM_WORLD_RANK=" + std::to_string(rank);
  std::vector<pid_t> candidates = descendants(job);
  if (candidates.empty()) candidates = naming(out);
  for (const pid_t p : candidates) {
    const std::string environ = t::slurp(fs::path("/proc") / std::to_string(p) / "environ");
    std::size_t at = 0;
    for (std::size_t end; (end = environ.find('\0', at)) != std::string::npos; at = end + 1)
      if (environ.compare(at, end - at, want) == 0) return p;
  }
  return -1;
}

std::map<std::string, t::FileId> files_below(const fs::path &dir) {
  std::map<std::string, t::FileId> out;
  for (const auto &e : fs::recursive_directory_iterator(dir))
    if (e.is_regular_file()) out[fs::relative(e.path(), dir).string()] = t::identify(e.path());
  return out;
}

int finished_cases(const fs::path &run) {
  int n = 0;
  for (int i = 0; i < t::mini_cases; ++i) n += t::finished(run / "cases" / t::case_id(i));
  return n;
}

// One try of the scene: three ranks (two workers). Both workers are frozen (SIGSTOP) the moment they
// are found and then let run in slices of a few milliseconds, frozen between slices, until a case is
// seen finished; worker rank 1 is then killed while both are still frozen, so no case can finish
// after the look. The slices make the test independent of how fast the machine runs a case: a slice
// is far shorter than a case. Returns mpirun's outcome.
t::Outcome kill_a_worker_midway(const std::vector<std::string> &args, const fs::path &run) {
  t::Child job(t::under_mpirun(3, args));
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::minutes(4);
  auto waiting = [&] { return job.running() && std::chrono::steady_clock::now() < deadline; };
  pid_t victim = -1, other = -1;
  while (waiting() && (victim <= 0 || other <= 0)) {
    if (victim <= 0) victim = rank_pid(1, job.pid(), run);
    if (other <= 0) other = rank_pid(2, job.pid(), run);
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  EXPECT_GT(victim, 0) << "rank 1 not found";
  EXPECT_GT(other, 0) << "rank 2 not found";
  if (victim <= 0 || other <= 0) return job.wait();
  auto freeze = [&] {
    ::kill(other, SIGSTOP);
    ::kill(victim, SIGSTOP);
  };
  freeze();
  while (waiting() && finished_cases(run) == 0) {
    ::kill(victim, SIGCONT);
    ::kill(other, SIGCONT);
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
    freeze();
  }
  EXPECT_TRUE(job.running()) << "the job ended before a rank could be killed";
  EXPECT_EQ(::kill(victim, SIGKILL), 0);  // mpirun then ends rank 2, stopped or not
  return job.wait();
}

}  // namespace

TEST(MpiKill, TheRerunComputesOnlyTheCasesTheKilledJobLeftUnfinished) {
  t::Scratch scratch("mpi_kill");
  const fs::path run = scratch.dir / "run";
  const std::vector<std::string> args = {"run", t::mini_quickstart().string(), "--out", run.string(), "--executor",
                                         "mpi"};

  // 1. kill a worker once a case is done. Should the workers finish every case within one slice
  // (which would leave nothing to prove), the scene is tried again from scratch (at most three tries).
  std::vector<std::string> done, todo;
  for (int attempt = 1; attempt <= 3 && todo.empty(); ++attempt) {
    fs::remove_all(run);
    done.clear();
    const t::Outcome first = kill_a_worker_midway(args, run);
    ASSERT_FALSE(::testing::Test::HasFailure()) << first.describe();
    EXPECT_FALSE(first.exited && first.exit_code == 0) << "mpirun must report the lost rank:\n" << first.describe();
    for (int i = 0; i < t::mini_cases; ++i)
      (t::finished(run / "cases" / t::case_id(i)) ? done : todo).push_back(t::case_id(i));
    if (todo.empty()) std::cerr << "try " << attempt << ": every case had finished when the worker was killed\n";
  }
  ASSERT_GE(done.size(), 1u);
  ASSERT_GE(todo.size(), 1u) << "every case finished before the kill, three times: the test proves nothing";
  for (const auto &id : todo) EXPECT_FALSE(fs::exists(run / "cases" / id / "case.json")) << id << ": a half result";

  std::map<std::string, t::FileId> kept;
  std::map<std::string, nlohmann::json> recorded;  // manifest entries of finished cases rank 0 had recorded
  const auto before = t::manifest(run);
  for (const auto &id : done) {
    for (const char *f : {"case.json", "state.vtp", "scene.json"})
      kept[id + "/" + f] = t::identify(run / "cases" / id / f);
    for (const auto &c : before.at("cases"))
      if (c.at("id") == id && c.value("status", "") == "done") recorded[id] = c;
  }
  const auto heaps = files_below(run / "heaps");

  // 2. the same command, on two ranks: only the unfinished cases run
  const t::Outcome second = t::run(t::under_mpirun(2, args));
  ASSERT_EQ(second.exit_code, 0) << second.describe();
  EXPECT_TRUE(t::contains(second.err, "4 cases, " + std::to_string(todo.size()) + " to run, " +
                                          std::to_string(done.size()) + " finished already"))
      << second.err;
  for (const auto &id : done) EXPECT_FALSE(t::contains(second.err, id + " done")) << id << " was recomputed";
  for (const auto &[file, id] : kept) EXPECT_EQ(t::identify(run / "cases" / file), id) << file << " was rewritten";
  EXPECT_EQ(files_below(run / "heaps"), heaps) << "the settled heap was recomputed";

  // every case present once, finished, recorded once; the old records kept
  const auto after = t::manifest(run);
  std::multiset<std::string> ids;
  for (const auto &c : after.at("cases")) {
    ids.insert(c.at("id").get<std::string>());
    EXPECT_EQ(c.value("status", ""), "done") << c.dump();
  }
  EXPECT_EQ(ids, (std::multiset<std::string>{"c000", "c001", "c002", "c003"}));
  for (const auto &[id, entry] : recorded)
    for (const auto &c : after.at("cases"))
      if (c.at("id") == id) {
        EXPECT_EQ(c.value("start", ""), entry.value("start", "")) << id;
        EXPECT_EQ(c.value("end", ""), entry.value("end", "")) << id;
      }
  for (int i = 0; i < t::mini_cases; ++i) {
    EXPECT_TRUE(t::finished(run / "cases" / t::case_id(i))) << i;
    EXPECT_FALSE(fs::exists(run / "cases" / t::case_id(i) / "checkpoint.bin")) << i;
  }
  const std::string csv = t::slurp(run / "metrics.csv");
  for (int i = 0; i < t::mini_cases; ++i) EXPECT_EQ(t::count(csv, "\n" + t::case_id(i) + ","), 1u) << csv;
}
