// bench_gpu: GPU throughput of the contact-force stage, in particle-steps per second, at the peers'
// scale (5,000 spheres) and the paper's (235,000), with the device's name. One "step" here is what
// the plugins' CUDA kernels do each DEM step: the roller's wall-contact records, the roller's wall
// forces and all pair forces (contact/hooke_slider with the viscous slider, as the peers' scene;
// history and accumulators stay on the device). Neighbour-list rebuilds and integration are not on
// the GPU yet and are not counted. The same stage through the engine's CPU loops (all cores) is timed
// alongside.
//
//   bench_gpu [--particles N ...] [--steps S] [--float]      (defaults: 5000 235000, 200 steps, double)
//
// Spheres: 250 um monodisperse Ti-6Al-4V in a jittered cubic lattice compressed by 1.2 % (about six
// touching neighbours each), random velocities; the roller cuts 0.3 mm into the top of the packing.
#include <spreadmap/contact.hpp>
#include <spreadmap/geometry.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <thread>
#include <vector>

#include "core/registry.hpp"
#include "engine/contact_loops.hpp"
#include "cuda/backend.hpp"
#include "cuda/device_state.hpp"
#include "cuda/forces.hpp"
#include "tests/gpu/plugin_params.hpp"
#include "tests/gpu/random_packing.hpp"

namespace sm = spreadmap;
using nlohmann::json;
using Clock = std::chrono::steady_clock;

namespace {

struct Scene {
  sm::PluginInstance pair_law, wall_law, roller;
  sm::cuda::ContactKernels pair_kernels, wall_kernels;
  sm::cuda::GeometryKernels roller_kernels;
};

Scene load_scene(double gap, double start) {
  auto &registry = sm::PluginRegistry::global();
  const auto &contact = registry.get("contact", "hooke_slider");
  const auto &roller = registry.get("spreader", "roller");
  Scene s{sm::PluginInstance(contact,
                             sm::test::plugin_params(contact.descriptor, {{"slider", "viscous"}, {"friction", 0.185}})),
          sm::PluginInstance(contact, sm::test::plugin_params(contact.descriptor, {{"friction", 0.12}})),
          sm::PluginInstance(roller,
                             sm::test::plugin_params(
                                 roller.descriptor,
                                 {{"diameter", 10e-3}, {"gap", gap}, {"start", start}, {"U", 0.1}, {"omega", -20.0}})),
          sm::cuda::contact_kernels(contact),
          sm::cuda::contact_kernels(contact),
          sm::cuda::spreader_kernels(roller)};
  return s;
}

template <class Real> void run(std::uint32_t n, int steps) {
  sm::test::PackingSpec spec;
  spec.n = n;
  spec.spread = 0;
  spec.history_values = 0;
  spec.dt = 7.5e-7;
  auto k = sm::test::make_packing<Real>(spec);
  const double top = *std::max_element(k.z.begin(), k.z.end());
  const double middle = 0.5 * double(k.box_hi[0] - k.box_lo[0]);
  Scene scene = load_scene(top - 0.3e-3, middle - 0.1 * 1e-3);  // axis over the middle at t = 1 ms
  auto records = sm::test::make_wall_records(k, spec);

  std::size_t touching = 0;
  for (std::uint32_t i = 0; i < k.n; ++i)
    for (std::uint32_t e = k.start[i]; e < k.start[i + 1]; ++e) {
      const std::uint32_t j = k.nbr[e];
      const double L = double(k.box_hi[0] - k.box_lo[0]);
      const double dx = sm::wrap(double(k.x[i] - k.x[j]), L, true), dy = sm::wrap(double(k.y[i] - k.y[j]), L, true);
      const double dz = double(k.z[i] - k.z[j]), reach = double(k.r[i] + k.r[j]);
      touching += dx * dx + dy * dy + dz * dz < reach * reach;
    }
  std::printf("\n%u particles (%s): %.2f list entries and %.2f touching neighbours per particle\n", n,
              sizeof(Real) == 8 ? "double" : "float", double(k.entries()) / n, double(touching) / n);

  // GPU: state resident on the device, three kernels per step, one synchronisation at the end.
  sm::cuda::select_device(0);
  sm::cuda::DeviceParticles<Real> dp;
  sm::cuda::DevicePairList<Real> dl;
  sm::cuda::DeviceWalls<Real> dw;
  dp.upload(k.particles());
  dl.upload(k.pairs(), k.n, scene.pair_kernels.ops->history);
  dw.upload(records.view(), scene.wall_kernels.ops->history);
  auto gpu_step = [&](int s) {
    dp.set_time(Real(1e-3 + s * spec.dt));
    const auto p = dp.view();
    sm::cuda::launch_geometry(scene.roller_kernels, scene.roller.get(), p, dw.view());
    sm::cuda::launch_walls(scene.wall_kernels, scene.wall_law.get(), p, dw.view());
    sm::cuda::launch_pairs(scene.pair_kernels, scene.pair_law.get(), p, dl.view());
  };
  for (int s = 0; s < 5; ++s) gpu_step(s);  // warm-up: module loading, caches
  sm::cuda::synchronize(0, "warm-up");
  const auto g0 = Clock::now();
  for (int s = 0; s < steps; ++s) gpu_step(s);
  sm::cuda::synchronize(0, "timed steps");
  const double gpu_seconds = std::chrono::duration<double>(Clock::now() - g0).count();
  const double gpu_rate = double(n) * steps / gpu_seconds;
  std::printf("  gpu: %d steps in %.4f s: %.3g particle-steps/s (%.1f us per step)\n", steps, gpu_seconds, gpu_rate,
              1e6 * gpu_seconds / steps);

  // CPU: the same three stages through the engine's CPU loops (its thread team, the plugins' queues and
  // ranges); the packing's list has no mirrors, so every entry is evaluated, as on the GPU.
  const sm::engine::ContactLaw pair_law{scene.pair_law.ops<sm::sm_contact_ops_v1>(), scene.pair_law.get()};
  const sm::engine::ContactLaw wall_law{scene.wall_law.ops<sm::sm_contact_ops_v1>(), scene.wall_law.get()};
  const sm::engine::GeometryWall roller{scene.roller.ops<sm::sm_spreader_ops_v2>(), scene.roller.get(), wall_law};
  const int cpu_steps = std::max(3, int(std::min<double>(steps, 2e7 / n)));
  auto p = k.particles();
  const auto l = k.pairs();
  const sm::engine::ListView<Real> list{l.start, l.nbr, l.hist};
  auto w = records.view();
  const auto c0 = Clock::now();
  for (int s = 0; s < cpu_steps; ++s) {
    p.t = Real(1e-3 + s * spec.dt);
    sm::engine::geometry_contacts(roller, p, w);
    sm::engine::wall_forces(wall_law, p, w);
    sm::engine::pair_forces(pair_law, p, list);
  }
  const double cpu_seconds = std::chrono::duration<double>(Clock::now() - c0).count();
  const double cpu_rate = double(n) * cpu_steps / cpu_seconds;
  std::printf("  cpu: %d steps in %.4f s: %.3g particle-steps/s (OMP_NUM_THREADS=%s, %u hardware threads)\n", cpu_steps,
              cpu_seconds, cpu_rate, std::getenv("OMP_NUM_THREADS") ? std::getenv("OMP_NUM_THREADS") : "unset",
              std::thread::hardware_concurrency());
  std::printf("  gpu / cpu: %.1f x\n", gpu_rate / cpu_rate);
}

}  // namespace

int main(int argc, char **argv) {
  std::vector<std::uint32_t> sizes;
  int steps = 200;
  bool single = false;
  for (int a = 1; a < argc; ++a) {
    if (!std::strcmp(argv[a], "--steps") && a + 1 < argc) steps = std::atoi(argv[++a]);
    else if (!std::strcmp(argv[a], "--float")) single = true;
    else if (!std::strcmp(argv[a], "--particles"))
      while (a + 1 < argc && argv[a + 1][0] != '-') sizes.push_back(std::uint32_t(std::atol(argv[++a])));
    else {
      std::fprintf(stderr, "usage: bench_gpu [--particles N ...] [--steps S] [--float]\n");
      return 2;
    }
  }
  if (sizes.empty()) sizes = {5000, 235000};
  const auto &probe = sm::cuda::probe_devices();
  if (probe.count == 0) {
    std::printf("bench_gpu: no CUDA device: %s\n", probe.why_none.c_str());
    return 1;
  }
  std::printf("bench_gpu: contact-force stage (roller records + roller wall forces + pair forces, hooke_slider)\n");
  std::printf("device: %s (CUDA device 0 of %d)\n", sm::cuda::device_name(0).c_str(), probe.count);
  try {
    for (const std::uint32_t n : sizes) single ? run<float>(n, steps) : run<double>(n, steps);
  } catch (const std::exception &e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 1;
  }
  return 0;
}
