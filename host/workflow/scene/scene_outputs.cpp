#include "workflow/scene/scene_outputs.hpp"

#include <fmt/format.h>

#include <cmath>
#include <iterator>

#include "core/files.hpp"

namespace spreadmap::scene {

namespace {

double wrap(double d, double length, bool periodic) {
  if (!periodic) return d;
  if (d > 0.5 * length) return d - length;
  if (d < -0.5 * length) return d + length;
  return d;
}

// Both tables are built in memory and written by write_atomic, as the .vtp beside them: every byte
// is checked on its way to the disk, so a full disk fails the command and leaves no short file under
// the final name (a stream checked before its last flush could).
void write_particles_csv(const fs::path &path, const engine::ParticleSet &s) {
  std::string out = "id,x,y,z,vx,vy,vz,wx,wy,wz,radius,mass,fixed\n";
  for (std::size_t i = 0; i < s.size(); ++i)
    fmt::format_to(std::back_inserter(out),
                   "{},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{}\n",
                   s.id[i], s.x[i], s.y[i], s.z[i], s.vx[i], s.vy[i], s.vz[i], s.wx[i], s.wy[i], s.wz[i], s.radius[i],
                   s.mass[i], s.fixed.empty() ? 0 : int(s.fixed[i]));
  write_atomic(path, out);
}

void write_contacts_csv(const fs::path &path, const std::vector<PairForce> &contacts) {
  std::string out = "id_i,id_j,fx,fy,fz,overlap\n";
  for (const auto &c : contacts)
    fmt::format_to(std::back_inserter(out), "{},{},{:.17g},{:.17g},{:.17g},{:.17g}\n", c.id_i, c.id_j, c.f[0],
                   c.f[1], c.f[2], c.overlap);
  write_atomic(path, out);
}

}  // namespace

std::vector<PairForce> pair_forces(engine::Simulation<double> &sim, const engine::ContactLaw &law) {
  const auto &p = sim.arrays();
  const auto &list = sim.neighbours();
  const engine::Domain &dom = sim.domain();
  const unsigned history = engine::law_history(law);
  std::vector<PairForce> out;
  if (list.start.size() != p.size() + 1) return out;  // no list yet: nothing has been evaluated
  for (std::uint32_t i = 0; i < p.size(); ++i)
    for (std::uint32_t k = list.start[i]; k < list.start[i + 1]; ++k) {
      const std::uint32_t j = list.nbr[k];
      if (j <= i) continue;
      const double d[3] = {wrap(p.x[i] - p.x[j], dom.length(0), dom.periodic[0]),
                           wrap(p.y[i] - p.y[j], dom.length(1), dom.periodic[1]),
                           wrap(p.z[i] - p.z[j], dom.length(2), dom.periodic[2])};
      const double overlap = p.r[i] + p.r[j] - std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
      if (!(overlap > 0)) continue;
      // the pair alone: particle 0 is i, 1 is j, and i's one neighbour is j
      const double x[2] = {p.x[i], p.x[j]}, y[2] = {p.y[i], p.y[j]}, z[2] = {p.z[i], p.z[j]};
      const double vx[2] = {p.vx[i], p.vx[j]}, vy[2] = {p.vy[i], p.vy[j]}, vz[2] = {p.vz[i], p.vz[j]};
      const double wx[2] = {p.wx[i], p.wx[j]}, wy[2] = {p.wy[i], p.wy[j]}, wz[2] = {p.wz[i], p.wz[j]};
      const double r[2] = {p.r[i], p.r[j]}, m[2] = {p.m[i], p.m[j]};
      double fx[2] = {0, 0}, fy[2] = {0, 0}, fz[2] = {0, 0}, tx[2] = {0, 0}, ty[2] = {0, 0}, tz[2] = {0, 0};
      Particles<double> two{2,  x,  y,  z,  vx, vy, vz, wx, wy, wz,       r,          m,
                            fx, fy, fz, tx, ty, tz, {}, {}, {}, sim.dt(), sim.time(), nullptr};
      for (int a = 0; a < 3; ++a) {
        two.box_lo[a] = dom.lo[a];
        two.box_hi[a] = dom.hi[a];
        two.periodic[a] = dom.periodic[a] ? 1 : 0;
      }
      const std::uint32_t start[3] = {0, 1, 1}, nbr[1] = {1};
      std::vector<double> hist(list.hist.begin() + std::size_t(k) * history,
                               list.hist.begin() + std::size_t(k + 1) * history);
      hist.push_back(0);  // never empty: the loop may take its address
      const PairList<double> one{start, nbr, hist.data()};
      law.ops->pairs_f64(law.self, &two, &one);
      out.push_back({p.id[i], p.id[j], {fx[0], fy[0], fz[0]}, overlap});
    }
  return out;
}

void SceneOutputs::write(engine::Simulation<double> &sim, const engine::ContactLaw &pair_law) {
  const std::size_t k = series_.size();
  const engine::ParticleSet state = sim.state();
  const std::string vtp = fmt::format("state_{:04d}.vtp", k);
  engine::write_vtp(dir_ / vtp, state, sim.time());
  if (particles_csv_) write_particles_csv(dir_ / fmt::format("particles_{:04d}.csv", k), state);
  if (contacts_csv_) write_contacts_csv(dir_ / fmt::format("contacts_{:04d}.csv", k), pair_forces(sim, pair_law));
  series_.push_back({sim.time(), vtp});
  engine::write_pvd(dir_ / "states.pvd", series_);
}

}  // namespace spreadmap::scene
