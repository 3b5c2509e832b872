#include "workflow/scene/scene_particles.hpp"

#include <fmt/format.h>
#include <spreadmap/sphere.hpp>

#include <algorithm>
#include <cmath>
#include <unordered_map>

#include "core/error.hpp"
#include "engine/csv_input.hpp"
#include "powder/heap.hpp"
#include "workflow/scene/scene_walls.hpp"

namespace spreadmap::scene {

namespace {

constexpr std::size_t problems_shown = 10;

SceneParticles generate(const SceneFile &scene) {
  const GeneratedParticles &g = scene.particles.generated;
  powder::HeapSpec spec;
  spec.region = {g.lo, g.hi};
  spec.count = static_cast<std::size_t>(g.count);
  spec.sizes = g.sigma > 0 ? powder::SizeDistribution::lognormal(g.diameter, g.sigma)
                           : powder::SizeDistribution::monodisperse(g.diameter);
  spec.seed = static_cast<std::uint64_t>(g.seed);
  spec.max_top = g.hi[2];  // the box is the region: it may not grow
  // clear of every wall by a twentieth of the sphere's diameter
  spec.excluded = [&](double x, double y, double z, double r) {
    for (const auto &w : scene.walls)
      if (wall_overlap(w, {x, y, z}, 1.1 * r) > 0) return true;
    return false;
  };
  powder::Heap heap;
  try {
    heap = powder::insert_heap(spec);
  } catch (const std::exception &e) {
    throw InputError(fmt::format(
        "{}: particles.generate: {}\n  give a larger box (lo, hi), fewer or smaller spheres, or move the walls "
        "that cut into the box",
        scene.file.string(), e.what()));
  }
  SceneParticles out;
  engine::ParticleSet &s = out.set;
  s.x = heap.x;
  s.y = heap.y;
  s.z = heap.z;
  s.radius = heap.r;
  const std::size_t n = heap.size();
  s.vx.assign(n, g.velocity[0]);
  s.vy.assign(n, g.velocity[1]);
  s.vz.assign(n, g.velocity[2]);
  return out;
}

// "file:line" of particle i, or "particle i" for generated ones.
std::string where(const SceneFile &scene, const SceneParticles &p, std::size_t i) {
  if (p.lines.empty()) return fmt::format("{}: particles.generate: particle {}", scene.file.string(), i);
  return fmt::format("{}:{}: particle {}", scene.particles.file.string(), p.lines[i], i);
}

void check_overlaps(const SceneFile &scene, const SceneParticles &p, std::vector<std::string> &problems) {
  const auto &s = p.set;
  const std::size_t n = s.size();
  if (n < 2) return;
  const double cell = 2 * *std::max_element(s.radius.begin(), s.radius.end());
  auto key = [&](long ix, long iy, long iz) {
    return (std::uint64_t(ix & 0x1fffff) << 42) | (std::uint64_t(iy & 0x1fffff) << 21) | std::uint64_t(iz & 0x1fffff);
  };
  auto index = [&](double v) { return static_cast<long>(std::floor(v / cell)); };
  std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> cells;
  for (std::size_t i = 0; i < n; ++i)
    cells[key(index(s.x[i]), index(s.y[i]), index(s.z[i]))].push_back(std::uint32_t(i));
  const double tol = scene.particles.overlap_tolerance;
  for (std::size_t i = 0; i < n && problems.size() < problems_shown; ++i) {
    const long cx = index(s.x[i]), cy = index(s.y[i]), cz = index(s.z[i]);
    for (long dx = -1; dx <= 1; ++dx)
      for (long dy = -1; dy <= 1; ++dy)
        for (long dz = -1; dz <= 1; ++dz) {
          const auto it = cells.find(key(cx + dx, cy + dy, cz + dz));
          if (it == cells.end()) continue;
          for (std::uint32_t j : it->second) {
            if (j <= i) continue;
            const double ddx = s.x[i] - s.x[j], ddy = s.y[i] - s.y[j], ddz = s.z[i] - s.z[j];
            const double overlap = s.radius[i] + s.radius[j] - std::sqrt(ddx * ddx + ddy * ddy + ddz * ddz);
            const double allowed = tol * 2 * std::min(s.radius[i], s.radius[j]);
            if (overlap > allowed && problems.size() < problems_shown)
              problems.push_back(fmt::format(
                  "{}: overlaps particle {} by {:.4g} m ({:.3g} of the smaller diameter, more than "
                  "particles.overlap_tolerance = {:g})\n  move them apart, or raise particles.overlap_tolerance",
                  where(scene, p, i), j, overlap, overlap / (2 * std::min(s.radius[i], s.radius[j])), tol));
          }
        }
  }
}

}  // namespace

SceneParticles load_particles(const SceneFile &scene) {
  SceneParticles out;
  if (scene.particles.generate) {
    out = generate(scene);
  } else {
    try {
      out.set = engine::read_particles_csv(scene.particles.file, &out.lines);
    } catch (const InputError &e) {
      throw InputError(
          fmt::format("{}\n  (the particle file of {}: particles.file; see docs/scenes.md for its columns)",
                      e.what(), scene.file.string()));
    }
    if (out.set.size() == 0)
      throw InputError(
          fmt::format("{}: no particles after the header\n  add one line per particle (particles.file of {})",
                      scene.particles.file.string(), scene.file.string()));
  }
  engine::ParticleSet &s = out.set;
  if (s.mass.empty()) {
    if (!(scene.particles.density > 0))
      throw InputError(fmt::format(
          "{}: particles.density: the particle file has neither a density nor a mass column\n  add a density "
          "column to {} or particles.density: <kg/m^3> to the scene",
          scene.particles.where.str(), scene.particles.file.string()));
    s.mass.resize(s.size());
    for (std::size_t i = 0; i < s.size(); ++i) s.mass[i] = sphere_mass(scene.particles.density, s.radius[i]);
  }
  return out;
}

void check_particles(const SceneFile &scene, const SceneParticles &p) {
  const auto &s = p.set;
  std::vector<std::string> problems;
  const auto &d = scene.domain;
  for (std::size_t i = 0; i < s.size() && problems.size() < problems_shown; ++i) {
    const Vec c{s.x[i], s.y[i], s.z[i]};
    for (int a = 0; a < 3; ++a)
      if (!d.periodic[a] && (c[a] < d.lo[a] || c[a] >= d.hi[a])) {
        problems.push_back(
            fmt::format("{}: {} = {:g} m is outside the domain [{:g}, {:g}) m along {}\n  move "
                        "the particle inside, widen domain (lo, hi) or make {} periodic",
                        where(scene, p, i), "xyz"[a], c[a], d.lo[a], d.hi[a], "xyz"[a], "xyz"[a]));
        break;
      }
    for (const auto &w : scene.walls) {
      const double overlap = wall_overlap(w, c, s.radius[i]);
      const double allowed = scene.particles.overlap_tolerance * 2 * s.radius[i];
      if (!(overlap > allowed)) continue;
      problems.push_back(
          overlap > s.radius[i]
              ? fmt::format("{}: its centre is on the wrong side of wall '{}' ({}): behind a plane, outside "
                            "a box or a tube, inside a block or a solid cylinder\n  move the particle, or the wall",
                            where(scene, p, i), w.name, w.key_path)
              : fmt::format("{}: sinks {:.4g} m into wall '{}' ({}), more than particles.overlap_tolerance = "
                            "{:g} of its diameter\n  move the particle or the wall apart",
                            where(scene, p, i), overlap, w.name, w.key_path, scene.particles.overlap_tolerance));
      break;
    }
  }
  if (problems.size() < problems_shown) check_overlaps(scene, p, problems);
  if (problems.empty()) return;
  std::string text;
  for (const auto &m : problems) text += (text.empty() ? "" : "\n") + m;
  if (problems.size() >= problems_shown) text += fmt::format("\n(the first {} problems are shown)", problems_shown);
  throw InputError(text);
}

}  // namespace spreadmap::scene
