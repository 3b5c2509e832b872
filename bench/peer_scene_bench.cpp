// bench_peer_scene: throughput of the simulate stage's spreading run on the peers' scene
// (workflows/peer_liggghts.yaml, the scene of the peers' LIGGGHTS runs): 5000 spheres of 250 um settled on a
// 2.5 mm periodic strip, a 10 mm roller at 100 mm/s (omega 0), hooke_slider with LIGGGHTS' viscous
// slider, the substrate plane, dt = 7.5e-7 s, double precision. The Simulation, its walls and its
// plugins are built by the same code as a case of the simulate stage (workflow/spreading/case_setup.hpp).
//
// It times `steps` spreading steps from the settled heap on each thread count, `repeats` times
// (interleaved, so that a slow spell of the machine hits every thread count alike), and prints the
// median particle-steps/s (particle count summed over the steps / wall time, as LIGGGHTS' figure),
// the speed-up, the machine, and LIGGGHTS' serial figure: the one given with --liggghts (measured in
// the same run by bench/peer_scene.sh), else the peers' recorded one, labelled as such. It also checks that
// every run ends in the bitwise same state (deterministic mode, any thread count).
//
// Usage: bench_peer_scene [--workflow FILE] [--heap FILE.vtp] [--save-heap FILE.vtp] [--steps N]
//          [--repeats R] [--threads 1,2] [--skip S] [--omega W] [--liggghts PS --liggghts-label TEXT]
//          [--backend cpu|cuda]
//   --backend cuda: the GPU mode, every step on the device (cuda/resident_stepper.hpp); the thread
//   counts then only set the host's OpenMP threads. With --workflow workflows/paper_full.yaml it times the
//   study's 235,000-sphere scene (its heap is settled first, on the same backend).
//   --heap: a settled heap (state .vtp, e.g. runs/peer_liggghts/heaps/heap_*.vtp); without it one is
//   settled first (~0.1 s of simulated time, a few minutes) and written to --save-heap if given.
//   --skip: spreading steps run once (not timed) before the timed ones; each repeat resumes there
//   from a checkpoint, as a resumed case does.
#include <omp.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <thread>
#include <time.h>
#include <csignal>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

#include "bench/bench_support.hpp"
#include "core/files.hpp"
#include "core/registry.hpp"
#include <spreadmap/simd.hpp>
#include "engine/vtp_io.hpp"
#include "workflow/stage_table.hpp"
#include "workflow/spreading/case_setup.hpp"
#include "workflow/spreading/scene_section.hpp"
#include "workflow/file/workflow.hpp"

namespace sm = spreadmap;
namespace fs = std::filesystem;

namespace {

// The peers' recorded LIGGGHTS figure: serial runs w0_s1/w0_s2 (6.35e6, 6.41e6) on a 2-core machine.
constexpr double liggghts_recorded = 6.4e6;

struct Options {
  fs::path workflow = fs::path(SPREADMAP_SOURCE_DIR) / "workflows" / "peer_liggghts.yaml";
  fs::path heap, save_heap;
  std::uint64_t steps = 20000, skip = 0;
  int repeats = 3;
  std::vector<int> threads{1, 2};
  double omega = 0;
  std::string backend = "cpu";
  bool busy = false;        // a busy process beside the runs, for the runs' whole time
  bool fixed_team = false;  // every step on all threads (no team tuner)
  double liggghts = liggghts_recorded;
  std::string liggghts_label = "the peers' recorded figure (serial, 2-core machine), NOT measured in this run";
};

[[noreturn]] void usage(const std::string &why) {
  sm::bench::usage_exit("bench_peer_scene",
                        "[--workflow FILE] [--heap FILE.vtp] [--save-heap FILE.vtp] [--steps N] [--repeats R] "
                        "[--threads 1,2] [--skip S] [--omega W] [--liggghts PS --liggghts-label TEXT] "
                        "[--backend cpu|cuda] [--busy] [--fixed-team]",
                        why);
}

Options parse(int argc, char **argv) {
  Options o;
  for (sm::bench::Args args(argc, argv, usage); args.next();) {
    const std::string &a = args.flag();
    if (a == "--workflow") o.workflow = args.value();
    else if (a == "--heap") o.heap = args.value();
    else if (a == "--save-heap") o.save_heap = args.value();
    else if (a == "--steps") o.steps = std::stoull(args.value());
    else if (a == "--skip") o.skip = std::stoull(args.value());
    else if (a == "--repeats") o.repeats = std::max(1, std::stoi(args.value()));
    else if (a == "--omega") o.omega = std::stod(args.value());
    else if (a == "--backend") o.backend = args.value();
    else if (a == "--busy") o.busy = true;
    else if (a == "--fixed-team") o.fixed_team = true;
    else if (a == "--liggghts") o.liggghts = std::stod(args.value());
    else if (a == "--liggghts-label") o.liggghts_label = args.value();
    else if (a == "--threads") o.threads = sm::bench::counts_in(args.value());
    else usage("unknown argument " + a);
  }
  if (o.threads.empty() || o.steps == 0) usage("need at least one thread count and one step");
  return o;
}

// CPU time of the whole process [s]: with one thread, the time it ran, whatever else the machine did.
double process_cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// A process that keeps one core busy until it is killed (--busy): another user's job on the machine.
struct BusyProcess {
  pid_t pid = -1;
  BusyProcess() {
    pid = ::fork();
    if (pid == 0) {
      ::prctl(PR_SET_PDEATHSIG, SIGKILL);  // never outlives a benchmark that was killed
      volatile unsigned long spin = 0;
      for (;;) spin = spin + 1;
    }
  }
  ~BusyProcess() {
    if (pid > 0) {
      ::kill(pid, SIGKILL);
      ::waitpid(pid, nullptr, 0);
    }
  }
};

struct Timing {
  double particle_steps_per_second;
  double neighbours;  // full-list entries per particle at the end
  std::uint64_t list_builds, removed;
  std::size_t particles_end;
  std::vector<double> end_state;
};

}  // namespace

int main(int argc, char **argv) {
  const Options opt = parse(argc, argv);
  spdlog::set_level(spdlog::level::warn);
  sm::PluginRegistry registry(sm::PluginRegistry::default_roots());

  // The peers' scene as the simulate stage resolves it; the case at omega (0 by default), heap seed 1.
  sm::Diagnostics diag;
  const auto resolved = sm::resolve_scene(sm::load_workflow(opt.workflow, sm::stage_names()), registry, diag);
  diag.throw_if_any();
  sm::Scene scene = *resolved;
  scene.spreader.params["omega"] = opt.omega;
  scene.backend = opt.backend;
  scene.powder.seed = 1;
  if (scene.precision != sm::Precision::float64) usage("the workflow's scene is not in double precision");

  sm::engine::ParticleSet heap;
  if (!opt.heap.empty()) {
    heap = sm::engine::read_vtp(opt.heap).particles;
    std::printf("heap: %zu spheres read from %s\n", heap.size(), opt.heap.c_str());
  } else {
    omp_set_num_threads(std::min(2, omp_get_num_procs()));
    std::printf("heap: settling %s s of a new heap (seed 1) ...\n",
                nlohmann::json(scene.powder.settle_time).dump().c_str());
    std::fflush(stdout);
    const auto t0 = std::chrono::steady_clock::now();
    heap = sm::settle_heap<double>(scene, registry, "bench", opt.workflow);
    std::printf("heap: %zu spheres settled in %.0f s\n", heap.size(),
                std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    if (!opt.save_heap.empty()) {
      sm::engine::write_vtp(opt.save_heap, heap, 0.0);
      std::printf("heap: written to %s (reuse it with --heap)\n", opt.save_heap.c_str());
    }
  }
  if (heap.size() != static_cast<std::size_t>(scene.powder.count))
    std::printf("warning: the heap has %zu spheres, the scene asks for %lld\n", heap.size(),
                static_cast<long long>(scene.powder.count));

  // --skip: one untimed run to the starting point, kept as a checkpoint every repeat resumes from.
  const fs::path checkpoint = fs::temp_directory_path() / ("bench_peer_scene_" + std::to_string(::getpid()) + ".bin");
  if (opt.skip > 0) {
    omp_set_num_threads(std::min(2, omp_get_num_procs()));
    auto run = sm::make_spreading_run<double>(scene, registry, heap, opt.workflow);
    run->sim.run_steps(opt.skip);
    run->sim.save_checkpoint(checkpoint);
  }

  const double dt = scene.time.step;
  std::printf(
      "bench_peer_scene: the spreading scene of %s, double precision, dt = %.3g s, omega = %g rad/s, backend %s\n",
      opt.workflow.filename().c_str(), dt, opt.omega, opt.backend.c_str());
  std::printf("machine: %s, %u hardware threads (OpenMP sees %d processors); load average at start %s\n",
              sm::bench::cpu_model().c_str(), std::thread::hardware_concurrency(), omp_get_num_procs(),
              sm::bench::load_average().c_str());
  std::printf("instruction set of the engine's loops: %s (SPREADMAP_SIMD=base|avx2|avx512 chooses)\n",
              sm::simd_name(sm::simd_level()));
  std::printf(
      "timed: %llu spreading steps from t = %.4g s (roller x = %.2f mm), %d repeats per thread count, "
      "interleaved\n",
      static_cast<unsigned long long>(opt.steps), opt.skip * dt,
      1e3 * (scene.spreader.params["start"].get<double>() + scene.spreader.params["U"].get<double>() * opt.skip * dt),
      opt.repeats);
  std::fflush(stdout);

  std::printf("threads: %s; %s\n",
              opt.fixed_team ? "every step on the run's thread count (--fixed-team)"
                             : "the team tuner chooses up to the run's thread count",
              opt.busy ? "a busy process runs beside the timed runs (--busy)" : "no other process started");
  std::fflush(stdout);
  std::unique_ptr<BusyProcess> busy;
  if (opt.busy) busy = std::make_unique<BusyProcess>();
  std::vector<std::vector<Timing>> timings(opt.threads.size());
  for (int r = 0; r < opt.repeats; ++r) {
    for (std::size_t k = 0; k < opt.threads.size(); ++k) {
      omp_set_num_threads(opt.threads[k]);
      auto run = sm::make_spreading_run<double>(scene, registry, heap, opt.workflow);
      auto &sim = run->sim;
      sim.tune_threads(!opt.fixed_team);
      if (opt.skip > 0) sim.load_checkpoint(checkpoint);
      const auto before = sim.counters();
      const auto t0 = std::chrono::steady_clock::now();
      const double cpu0 = process_cpu_seconds();
      sim.run_steps(opt.steps);
      const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      const double cpu = process_cpu_seconds() - cpu0;
      const auto &after = sim.counters();
      const double particle_steps = after.particle_steps - before.particle_steps;
      const auto &pa = after.profile, &pb = before.profile;
      const double parts[] = {pa.integrate - pb.integrate, pa.neighbours - pb.neighbours, pa.pairs - pb.pairs,
                              pa.planes - pb.planes,       pa.geometries - pb.geometries, pa.other - pb.other};
      Timing t{particle_steps / wall,
               double(sim.list_entries()) / double(std::max<std::size_t>(1, sim.size())),
               after.list_builds - before.list_builds,
               sim.removed_count(),
               sim.size(),
               sim.state().kinematics_by_id()};
      std::printf(
          "  repeat %d, %d thread%s: %.3e particle-steps/s (%.1f ns per particle-step; CPU time of all "
          "threads %.1f ns), %llu list builds, %.2f neighbours per particle (full list), %zu particles at the "
          "end\n",
          r + 1, opt.threads[k], opt.threads[k] > 1 ? "s" : " ", t.particle_steps_per_second,
          1e9 / t.particle_steps_per_second, 1e9 * cpu / particle_steps, static_cast<unsigned long long>(t.list_builds),
          t.neighbours, t.particles_end);
      double timed = 0;
      for (double x : parts) timed += x;
      std::printf(
          "    where the step's time went: integrate %.1f %%, neighbour list %.1f %%, pairs %.1f %%, plane walls "
          "%.1f %%, spreader %.1f %%, other %.1f %%\n",
          100 * parts[0] / timed, 100 * parts[1] / timed, 100 * parts[2] / timed, 100 * parts[3] / timed,
          100 * parts[4] / timed, 100 * parts[5] / timed);
      std::fflush(stdout);
      timings[k].push_back(std::move(t));
    }
  }
  busy.reset();
  std::error_code ec;
  fs::remove(checkpoint, ec);

  bool identical = true;
  const auto &reference = timings[0][0].end_state;
  for (const auto &per_threads : timings)
    for (const auto &t : per_threads)
      identical = identical && t.end_state.size() == reference.size() &&
                  std::memcmp(t.end_state.data(), reference.data(), reference.size() * sizeof(double)) == 0;

  std::printf("\nload average at the end %s\n", sm::bench::load_average().c_str());
  std::printf("end states of all %d runs bitwise identical (any thread count): %s\n",
              int(opt.threads.size()) * opt.repeats, identical ? "yes" : "NO");
  // the first run's end state hashed: the same heap and steps on another commit should print the same
  const std::string end_bytes(reinterpret_cast<const char *>(reference.data()), reference.size() * sizeof(double));
  std::printf("end state digest (stable_hash of positions and velocities by id): %s\n",
              sm::stable_hash(end_bytes).c_str());
  std::printf("\n%-28s %16s %12s %12s\n", "", "particle-steps/s", "speed-up", "x LIGGGHTS");
  std::vector<double> med(opt.threads.size());
  for (std::size_t k = 0; k < opt.threads.size(); ++k) {
    std::vector<double> v;
    for (const auto &t : timings[k]) v.push_back(t.particle_steps_per_second);
    med[k] = median(v);
  }
  for (std::size_t k = 0; k < opt.threads.size(); ++k) {
    const std::string name =
        "spreadmap, " + std::to_string(opt.threads[k]) + " thread" + (opt.threads[k] > 1 ? "s" : "");
    std::printf("%-28s %16.3e %12.2f %12.2f   (median of %d)\n", name.c_str(), med[k], med[k] / med[0],
                med[k] / opt.liggghts, opt.repeats);
  }
  std::printf("%-28s %16.3e %12s %12.2f   %s\n", "LIGGGHTS 3.8, 1 process", opt.liggghts, "", 1.0,
              opt.liggghts_label.c_str());

  // Issue 41's targets: >= 6x LIGGGHTS' serial figure on one thread (10x the moonshot); from 1 to 2
  // threads >= 1.85 on a quiet machine, and >= 0.9 beside a busy process (--busy).
  for (std::size_t k = 0; k < opt.threads.size(); ++k) {
    if (opt.threads[k] == 1)
      std::printf("target 1 thread >= 6x LIGGGHTS serial: %.2fx -> %s\n", med[k] / opt.liggghts,
                  med[k] >= 6 * opt.liggghts ? "met" : "NOT met");
    if (opt.threads[k] == 2 && opt.threads[0] == 1) {
      const double wanted = opt.busy ? 0.9 : 1.85;
      std::printf("target 2 threads / 1 thread >= %.2f (%s): %.2f -> %s\n", wanted,
                  opt.busy ? "beside a busy process" : "quiet machine", med[k] / med[0],
                  med[k] >= wanted * med[0] ? "met" : "NOT met");
    }
  }
  return identical ? 0 : 1;
}
