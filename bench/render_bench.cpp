// Renders a 235,000-particle snapshot (the study's scene size) at 1920x1080 and prints the wall
// time with the number of cores; target: under 30 s on 2 cores (software GL in a private Xvfb).
#include <spreadmap/render/figures.hpp>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <thread>

namespace r = spreadmap::render;

int main(int argc, char** argv) {
  const int count = argc > 1 ? std::atoi(argv[1]) : 235000;
  // A settled heap: spheres of 250 um on a jittered lattice under a sine-shaped profile.
  r::SnapshotInput s;
  s.domain.lo = {0, 0, 0};
  s.domain.hi = {0.08, 0.0025, 0.025};  // tall enough for the stacked lattice
  const double d = 250e-6;
  std::uint64_t state = 7;
  auto uniform = [&state] {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    return static_cast<double>(state >> 11) * (1.0 / 9007199254740992.0);
  };
  const int ny = 10;
  for (int i = 0; static_cast<int>(s.x.size()) < count; ++i) {
    const int ix = i / ny % 240, iy = i % ny, iz = i / (ny * 240);
    const double x = 0.01 + (ix + 0.1 * uniform()) * d, y = (iy + 0.5) * d, z = (iz + 0.5) * d * 0.9;
    s.x.push_back(x);
    s.y.push_back(y);
    s.z.push_back(z);
    s.r.push_back(0.5 * d);
    s.speed.push_back(0.1 * uniform() * z / 0.02);
  }
  for (int k = 0; k < 72; ++k) {  // a 10 mm roller's disc, turned by 1 rad
    s.spreader.outline_x.push_back(0.005 * std::cos(2 * 3.14159265358979 * k / 72));
    s.spreader.outline_z.push_back(0.005 * std::sin(2 * 3.14159265358979 * k / 72));
  }
  s.spreader.reference = {0.075, 0.00125, 0.0055};
  s.spreader.length = 0.07;
  s.spreader.turns = true;
  s.spreader.angle = 1.0;
  r::Options o;
  o.width = 1920;
  o.height = 1080;
  o.title = "bench_render: " + std::to_string(count) + " particles";
  const auto png = std::filesystem::temp_directory_path() / "spreadmap_bench_render.png";
  const auto t0 = std::chrono::steady_clock::now();
  r::snapshot(s, png, o);
  const double first = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const auto t1 = std::chrono::steady_clock::now();
  r::snapshot(s, png, o);
  const double second = std::chrono::duration<double>(std::chrono::steady_clock::now() - t1).count();
  std::printf("bench_render: %d particles, 1920x1080, %u cores: first %.2f s (incl. Xvfb start), next %.2f s -> %s\n",
              count, std::thread::hardware_concurrency(), first, second, png.c_str());
  return 0;
}
