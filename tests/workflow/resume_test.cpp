// Kill and resume: `spreadmap run` is interrupted with SIGINT once its first case has finished. It
// must stop cleanly (exit 130, a message saying how to resume, no half-written file anywhere); the
// same command then runs only the unfinished cases — the finished ones keep their files untouched
// (same inode and modification time: write_atomic would have replaced the inode) and their manifest
// timings — and a third run recomputes nothing at all. A multi-layer case (Layers.*) resumes at the
// layer it was on.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
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

namespace {

const fs::path two_layers = fs::path(SPREADMAP_SOURCE_DIR) / "tests/workflow/data/multilayer/two_layers.yaml";

std::vector<std::vector<std::string>> csv_rows(const fs::path &file) {
  std::vector<std::vector<std::string>> rows;
  std::ifstream in(file);
  for (std::string line; std::getline(in, line);) {
    std::vector<std::string> cells;
    std::stringstream s(line);
    for (std::string cell; std::getline(s, cell, ',');) cells.push_back(cell);
    rows.push_back(cells);
  }
  return rows;
}

std::size_t column(const std::vector<std::string> &header, const std::string &name) {
  return std::size_t(std::find(header.begin(), header.end(), name) - header.begin());
}

// Spheres in a state.vtp, as its header says.
std::size_t spheres_in(const fs::path &vtp) {
  const std::string text = slurp(vtp), tag = "NumberOfPoints=\"";
  const auto at = text.find(tag);
  return at == std::string::npos ? 0 : std::stoul(text.substr(at + tag.size()));
}

}  // namespace

// Two layers of a tiny scene: the second heap is spread onto the first layer's bed. The bed holds
// more powder in the sampling region after the second pass, every sphere is accounted for (two heaps
// fed, less those the engine removed), metrics.csv has a row per layer, and layer 1 is exactly the
// single-pass case of the same scene.
TEST(Layers, TheSecondLayerAddsPowderAndEverySphereIsCounted) {
  const fs::path dir = fs::temp_directory_path() / ("spreadmap_layers_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  const t::Outcome r = t::run({{"run", two_layers.string(), "--out", (dir / "two").string()}, {}, {}, {}});
  ASSERT_EQ(r.exit_code, 0) << r.describe();
  const fs::path c = dir / "two" / "cases" / "c000";

  const auto rows = csv_rows(dir / "two" / "metrics.csv");
  ASSERT_EQ(rows.size(), 3u);
  ASSERT_GE(rows[0].size(), 2u);
  EXPECT_EQ(rows[0][1], "layer");
  const std::size_t in_region = column(rows[0], "particles_in_region"), top = column(rows[0], "layer_height");
  ASSERT_LT(in_region, rows[0].size());
  ASSERT_LT(top, rows[0].size());
  EXPECT_EQ(rows[1][1], "1");
  EXPECT_EQ(rows[2][1], "2");
  EXPECT_GT(std::stod(rows[2][in_region]), std::stod(rows[1][in_region])) << "the second layer added no powder";
  // a layer's relative density: the solid the pass added over the platform's drop (0.3 mm), layer 1's
  // over its gap (0.5 mm)
  const std::size_t solid = column(rows[0], "solid_thickness"), density = column(rows[0], "layer_relative_density");
  ASSERT_LT(density, rows[0].size());
  const double s1 = std::stod(rows[1][solid]), s2 = std::stod(rows[2][solid]);
  EXPECT_NEAR(std::stod(rows[1][density]), s1 / 0.5e-3, 1e-9);
  EXPECT_NEAR(std::stod(rows[2][density]), (s2 - s1) / 0.3e-3, 1e-9);
  EXPECT_GT(std::stod(rows[2][density]), 0.0);
  EXPECT_LT(std::stod(rows[2][density]), 0.74) << "no denser than the closest packing of spheres";

  const auto cj = nlohmann::json::parse(slurp(c / "case.json"));
  ASSERT_EQ(cj.at("layers").size(), 2u);
  std::size_t fed = 0, removed = 0;
  for (const auto &l : cj["layers"]) {
    fed += l.at("particles_fed").get<std::size_t>();
    removed += l.at("removed").get<std::size_t>() + l.at("removed_settling").get<std::size_t>();
  }
  const std::size_t heap = cj["layers"][0]["particles_fed"].get<std::size_t>();
  EXPECT_EQ(heap, 300u);
  EXPECT_GT(cj["layers"][1]["particles_fed"].get<std::size_t>(), heap / 2);  // less those kept clear of the roller
  EXPECT_LE(cj["layers"][1]["particles_fed"].get<std::size_t>(), heap);
  EXPECT_EQ(spheres_in(c / "layer_1" / "state.vtp") + cj["layers"][1]["particles_fed"].get<std::size_t>() -
                cj["layers"][1]["removed"].get<std::size_t>() - cj["layers"][1]["removed_settling"].get<std::size_t>(),
            spheres_in(c / "layer_2" / "state.vtp"));
  EXPECT_EQ(spheres_in(c / "state.vtp"), fed - removed);
  EXPECT_EQ(cj.at("particles_end").get<std::size_t>(), fed - removed);
  EXPECT_EQ(slurp(c / "state.vtp"), slurp(c / "layer_2" / "state.vtp"));
  EXPECT_DOUBLE_EQ(cj["layers"][1]["platform_drop"].get<double>(), 0.3e-3);
  EXPECT_DOUBLE_EQ(cj["layers"][1]["spreader"]["gap"].get<double>(), 0.5e-3 + 0.3e-3);

  // the same scene in one layer: its state is layer 1's, and its metrics.csv has no layer column
  std::string one = slurp(two_layers);
  one.erase(one.find("  layers:"), one.find('\n', one.find("  layers:")) - one.find("  layers:") + 1);
  std::ofstream(dir / "one.yaml") << one;
  const t::Outcome single = t::run({{"run", (dir / "one.yaml").string(), "--out", (dir / "one").string()}, {}, {}, {}});
  ASSERT_EQ(single.exit_code, 0) << single.describe();
  EXPECT_EQ(slurp(dir / "one" / "cases" / "c000" / "state.vtp"), slurp(c / "layer_1" / "state.vtp"));
  const auto single_rows = csv_rows(dir / "one" / "metrics.csv");
  ASSERT_EQ(single_rows.size(), 2u);
  EXPECT_EQ(column(single_rows[0], "layer"), single_rows[0].size());
  EXPECT_EQ(column(single_rows[0], "layer_height"), single_rows[0].size());
  EXPECT_EQ(column(single_rows[0], "layer_relative_density"), single_rows[0].size());
  fs::remove_all(dir);
}

// A run stopped after its first layer (the second layer's files gone, as when a run is killed
// during it) resumes at layer 2: layer 1's files are neither rewritten nor recomputed, and the
// result is the uninterrupted run's, bit for bit.
TEST(Layers, AStoppedRunResumesAtItsLayerAndNeverRecomputesAFinishedOne) {
  const fs::path dir = fs::temp_directory_path() / ("spreadmap_layers_resume_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  const t::Command command{{"run", two_layers.string(), "--out", dir.string()}, {}, {}, {}};
  ASSERT_EQ(t::run(command).exit_code, 0);
  const fs::path c = dir / "cases" / "c000";
  const std::string whole = slurp(c / "state.vtp"), second = slurp(c / "layer_2" / "state.vtp");
  const FileId layer1 = identify(c / "layer_1" / "state.vtp"), record1 = identify(c / "layer_1" / "layer.json");
  fs::remove_all(c / "layer_2");
  for (const char *f : {"case.json", "state.vtp", "metrics.json"}) fs::remove(c / f);

  const t::Outcome resumed = t::run(command);
  ASSERT_EQ(resumed.exit_code, 0) << resumed.describe();
  EXPECT_TRUE(contains(resumed.err, "1 cases, 1 to run, 0 finished already")) << resumed.err;
  EXPECT_TRUE(contains(resumed.err, "c000 layer 1: finished before")) << resumed.err;
  EXPECT_TRUE(contains(resumed.err, "c000 layer 2: heap fed onto the bed settled")) << resumed.err;
  EXPECT_EQ(identify(c / "layer_1" / "state.vtp"), layer1) << "layer 1 was rewritten";
  EXPECT_EQ(identify(c / "layer_1" / "layer.json"), record1) << "layer 1 was rewritten";
  EXPECT_EQ(slurp(c / "layer_2" / "state.vtp"), second);
  EXPECT_EQ(slurp(c / "state.vtp"), whole);
  EXPECT_EQ(temporaries(dir), std::vector<std::string>{});
  fs::remove_all(dir);
}
