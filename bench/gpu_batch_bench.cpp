// bench_gpu_batch (CUDA builds, a GPU): throughput of many cases stepping at once on one GPU, as the
// simulate stage runs them with backend cuda (cuda/resident_stepper.hpp: each case on its own stream,
// stepped from its own host thread; one host thread a CPU core, workflow/executors/local_executor.hpp).
//
// The cases are the first N points of the workflow's simulate design (default workflows/paper.yaml:
// the paper strip's 5 x 9 map), each stepping `steps` spreading steps from one heap settled on the
// GPU. For each N it prints the wall time and the particle-steps per second of all cases together,
// and checks that the design's first case, stepped beside the others, ends bitwise as it does alone
// (the N = 1 run). The device and the host's processor are printed with the figures.
//
// Usage: bench_gpu_batch [--workflow FILE] [--cases 1,8,45] [--steps S] [--host-threads T]
//   --host-threads: cases stepped at once (default: the host's hardware threads, as the simulate stage)
#include <spdlog/spdlog.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "bench/bench_support.hpp"
#include "core/registry.hpp"
#include "cuda/backend.hpp"
#include "workflow/file/workflow.hpp"
#include "workflow/simulate/design.hpp"
#include "workflow/spreading/case_setup.hpp"
#include "workflow/spreading/scene_section.hpp"
#include "workflow/stage_table.hpp"

namespace sm = spreadmap;
namespace fs = std::filesystem;

namespace {

struct Options {
  fs::path workflow = fs::path(SPREADMAP_SOURCE_DIR) / "workflows" / "paper.yaml";
  std::vector<std::size_t> cases{1, 8, 45};
  std::uint64_t steps = 10000;
  unsigned host_threads = std::max(1u, std::thread::hardware_concurrency());
};

[[noreturn]] void usage(const std::string &why) {
  sm::bench::usage_exit("bench_gpu_batch", "[--workflow FILE] [--cases 1,8,45] [--steps S] [--host-threads T]", why);
}

Options parse(int argc, char **argv) {
  Options o;
  for (sm::bench::Args args(argc, argv, usage); args.next();) {
    const std::string &a = args.flag();
    if (a == "--workflow") o.workflow = args.value();
    else if (a == "--steps") o.steps = std::stoull(args.value());
    else if (a == "--host-threads") o.host_threads = unsigned(std::max(1, std::stoi(args.value())));
    else if (a == "--cases") {
      o.cases.clear();
      for (int n : sm::bench::counts_in(args.value())) o.cases.push_back(std::size_t(n));
    } else usage("unknown argument " + a);
  }
  if (o.cases.empty() || o.steps == 0) usage("need at least one batch and one step");
  return o;
}

struct Batch {
  double wall = 0, particle_steps = 0;
  std::vector<double> first_case;  // the design's first case's end state
};

// The design's first `n` cases from `heap`, stepped by min(n, host_threads) threads that each take
// the next unstarted case, as the simulate stage's pool does.
Batch run_batch(const std::vector<sm::Scene> &scenes, std::size_t n, const sm::engine::ParticleSet &heap,
                const Options &opt, sm::PluginRegistry &registry) {
  std::vector<std::unique_ptr<sm::SpreadingRun<double>>> runs;
  for (std::size_t c = 0; c < n; ++c)
    runs.push_back(sm::make_spreading_run<double>(scenes[c], registry, heap, opt.workflow));
  std::atomic<std::size_t> next{0};
  std::vector<std::string> errors(n);
  auto worker = [&] {
    for (std::size_t c = next++; c < n; c = next++) try {
        runs[c]->sim.run_steps(opt.steps);
      } catch (const std::exception &e) {
        errors[c] = e.what();
      }
  };
  const auto t0 = std::chrono::steady_clock::now();
  std::vector<std::thread> threads;
  for (std::size_t t = 0; t < std::min<std::size_t>(n, opt.host_threads); ++t) threads.emplace_back(worker);
  for (auto &t : threads) t.join();
  Batch b;
  b.wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  for (std::size_t c = 0; c < n; ++c) {
    if (!errors[c].empty()) {
      std::fprintf(stderr, "bench_gpu_batch: case %zu failed: %s\n", c, errors[c].c_str());
      std::exit(1);
    }
    b.particle_steps += runs[c]->sim.counters().particle_steps;
  }
  b.first_case = runs[0]->sim.state().kinematics_by_id();
  return b;
}

}  // namespace

int main(int argc, char **argv) {
  const Options opt = parse(argc, argv);
  spdlog::set_level(spdlog::level::warn);
  if (sm::cuda::device_count() == 0) {
    std::fprintf(stderr, "bench_gpu_batch: no CUDA device: %s\n", sm::cuda::probe_devices().why_none.c_str());
    return 2;
  }
  sm::PluginRegistry registry(sm::PluginRegistry::default_roots());

  // The workflow's scene on the GPU and its simulate design, as the simulate stage resolves them.
  sm::Diagnostics diag;
  const sm::Workflow wf = sm::load_workflow(opt.workflow, sm::stage_names());
  const auto resolved = sm::resolve_scene(wf, registry, diag);
  diag.throw_if_any();
  sm::Scene scene = *resolved;
  scene.backend = "cuda";
  if (scene.precision != sm::Precision::float64) usage("the workflow's scene is not in double precision");
  const auto stage = std::find_if(wf.stages.begin(), wf.stages.end(), [](auto &s) { return s.kind == "simulate"; });
  if (stage == wf.stages.end()) usage("the workflow has no simulate stage");
  const sm::Design design =
      sm::parse_design(stage->config["design"], wf.file.string(), "simulate.design", scene, registry, diag);
  diag.throw_if_any();
  const std::size_t most = *std::max_element(opt.cases.begin(), opt.cases.end());
  if (design.cases.size() < most) usage("the workflow's design has fewer cases than the largest batch");
  std::vector<sm::Scene> scenes;
  for (std::size_t c = 0; c < most; ++c) scenes.push_back(sm::case_scene(scene, design, c));

  std::printf("bench_gpu_batch: %s, its first cases of %zu, %llu spreading steps each, double precision\n",
              opt.workflow.filename().c_str(), design.cases.size(), static_cast<unsigned long long>(opt.steps));
  std::printf("device: %s; host: %s, %u hardware threads, %u cases stepped at once at most; load average %s\n",
              sm::cuda::probe_devices().device.c_str(), sm::bench::cpu_model().c_str(),
              std::thread::hardware_concurrency(), opt.host_threads, sm::bench::load_average().c_str());
  std::fflush(stdout);
  const auto t0 = std::chrono::steady_clock::now();
  const auto heap = sm::settle_heap<double>(scenes[0], registry, "bench", opt.workflow);
  std::printf("heap: %zu spheres settled on the GPU in %.0f s\n", heap.size(),
              std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());

  std::printf("%8s %10s %18s %16s %16s\n", "cases", "wall [s]", "particle-steps/s", "x one case", "case 0 as alone");
  std::vector<double> alone;
  double alone_rate = 0;
  for (std::size_t n : opt.cases) {
    const Batch b = run_batch(scenes, n, heap, opt, registry);
    const double rate = b.particle_steps / b.wall;
    if (alone.empty() && n == 1) alone = b.first_case, alone_rate = rate;
    const bool same = !alone.empty() && alone.size() == b.first_case.size() &&
                      std::memcmp(alone.data(), b.first_case.data(), alone.size() * sizeof(double)) == 0;
    std::printf("%8zu %10.2f %18.3g %16.2f %16s\n", n, b.wall, rate, alone_rate > 0 ? rate / alone_rate : 0.0,
                alone.empty() ? "(no N = 1 run)"
                : same        ? "bitwise"
                              : "DIFFERS");
    std::fflush(stdout);
  }
  std::printf("load average at the end %s\n", sm::bench::load_average().c_str());
  return 0;
}
