// bench_layer: characterise a paper-sized layer (235,000 spheres of 250 um: a jittered bottom layer
// plus a random partial second layer, ~1.3 diameters thick) on the study's 50 mm x 50 mm sampling
// region at cell d/5, and print the wall time with the number of threads. Target: under 2 s on
// 2 cores. Also times the worst case where all 235,000 spheres lie inside the region (~5 d deep).
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "layer_metrics.hpp"

namespace {

namespace layer = spreadmap::layer;
constexpr double d = 250e-6, r = d / 2;
constexpr std::size_t count = 235000;

struct Scene {
  std::vector<double> x, y, z, rad;
  sm_layer_input_v1 input{};
};

void finish(Scene &s, double region_x0, double region_y0, double strip_width) {
  sm_layer_input_v1 &in = s.input;
  in.n = s.x.size();
  in.x = s.x.data();
  in.y = s.y.data();
  in.z = s.z.data();
  in.r = s.rad.data();
  in.region[0] = region_x0;
  in.region[1] = region_x0 + 50e-3;
  in.region[2] = region_y0;
  in.region[3] = region_y0 + 50e-3;
  in.periodic_y[0] = 0;
  in.periodic_y[1] = strip_width;
  in.speed = 0.1;
  in.gap = 2 * d;
}

// A spread-like layer ~1.3 d thick: 77 % of the spheres on a jittered square grid of pitch 1.1 d
// resting on the substrate, the other 23 % at random in a second layer sitting in the hollows.
// The strip is 70 mm wide and periodic in y, as in a DEM run; its length follows from the count.
Scene layer_scene(double &length) {
  const double pitch = 1.1 * d, width = 70e-3;
  const std::size_t bottom = static_cast<std::size_t>(0.77 * count);
  const long columns = std::lround(width / pitch), rows = static_cast<long>((bottom + columns - 1) / columns);
  length = rows * pitch;
  Scene s;
  std::mt19937_64 rng(2024);
  std::uniform_real_distribution<double> jitter(-0.04 * d, 0.04 * d), ux(0, length), uy(0, width);
  for (long i = 0; i < rows && s.x.size() < bottom; ++i)
    for (long j = 0; j < columns && s.x.size() < bottom; ++j) {
      s.x.push_back((i + 0.5) * pitch + jitter(rng));
      s.y.push_back((j + 0.5) * pitch + jitter(rng));
      s.z.push_back(r);
    }
  while (s.x.size() < count) {
    s.x.push_back(ux(rng));
    s.y.push_back(uy(rng));
    s.z.push_back(r + 0.8 * d);
  }
  s.rad.assign(count, r);
  finish(s, 0.5 * length - 25e-3, 10e-3, width);
  return s;
}

// Worst case: every sphere inside the region, random centres up to ~5 d deep (overlaps allowed).
Scene heap_scene() {
  Scene s;
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> ux(0, 50e-3), uz(r, 5 * d);
  for (std::size_t i = 0; i < count; ++i) {
    s.x.push_back(ux(rng));
    s.y.push_back(ux(rng));
    s.z.push_back(uz(rng));
  }
  s.rad.assign(count, r);
  finish(s, 0, 0, 50e-3);
  return s;
}

double best_seconds(const sm_layer_input_v1 &in, int repeats, layer::LayerResult &out) {
  double best = 1e30;
  for (int k = 0; k < repeats; ++k) {
    const auto t0 = std::chrono::steady_clock::now();
    out = layer::characterise_layer(in, 0.0);  // default cell: d/5
    const std::string json = layer::metrics_json(out);
    const auto t1 = std::chrono::steady_clock::now();
    best = std::min(best, std::chrono::duration<double>(t1 - t0).count());
  }
  return best;
}

void run(const char *label, const Scene &s, int max_threads) {
  layer::LayerResult result;
  std::printf("%s\n", label);
  for (int threads : {1, max_threads}) {
    omp_set_num_threads(threads);
    const double t = best_seconds(s.input, 3, result);
    std::printf("  threads %d: %.3f s (best of 3)  grid %u x %u, cell %.1f um\n", threads, t, result.grid.nx,
                result.grid.ny, result.metrics.cell * 1e6);
    if (max_threads == 1) break;
  }
  const auto &m = result.metrics;
  std::printf(
      "  particles in region %llu, mean height %.1f um, rq %.1f um, solid %.1f um, coverage %.4f, "
      "packing %.3f\n",
      static_cast<unsigned long long>(m.particles_in_region), m.mean_height * 1e6, m.rq * 1e6, m.solid_thickness * 1e6,
      m.coverage, m.packing_fraction);
}

}  // namespace

int main() {
  std::printf(
      "bench_layer: %zu spheres of %.0f um, region 50 mm x 50 mm, cell d/5; hardware threads %u, "
      "OpenMP max threads %d\n",
      count, d * 1e6, std::thread::hardware_concurrency(), omp_get_max_threads());
  const int max_threads = omp_get_max_threads();
  double length = 0;
  const Scene layer = layer_scene(length);
  std::printf("strip %.1f mm x 70 mm, periodic in y\n", length * 1e3);
  run("spread layer ~1.3 d thick (region in the middle of the strip)", layer, max_threads);
  run("all spheres inside the region (~5 d deep, worst case)", heap_scene(), max_threads);
  std::printf("target: under 2 s on 2 cores\n");
  return 0;
}
