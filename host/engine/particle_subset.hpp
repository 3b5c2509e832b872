// A few particles copied out of the engine's arrays, so that a plugin loop (geometry contacts, a
// wall law) runs over them alone instead of over every particle: the spreader touches a few hundred
// particles of thousands. Forces start at zero in the copy and are added back afterwards, which
// gives the same sums as the plugin adding to the full arrays directly (x + (0 + c) == x + c).
#pragma once
#include <engine/particle_arrays.hpp>
#include <engine/thread_team.hpp>
#include <spreadmap/batch.hpp>

#include <cstdint>
#include <vector>

namespace spreadmap::engine {

template <class Real> class ParticleSubset {
 public:
  // Smaller copies are made on the calling thread: starting a team would cost more.
  static constexpr std::size_t parallel_from = 4096;

  // Copies the state of particles `index` (and their wall history, `history` values each) and
  // clears the force accumulators and wall records of the copy.
  void gather(const ParticleArrays<Real> &p, const std::vector<std::uint32_t> &index, const std::vector<Real> &hist,
              unsigned history) {
    size_for(index, history);
    const std::size_t n = index.size();
    parallel_for(
        this_thread_team(), n, [&](long long q) { gather(p, hist, std::size_t(q), std::size_t(q) + 1); },
        n > parallel_from);
  }

  // The same in parts, for a caller that shares the copy between its threads: size_for once, then
  // gather each part [lo, hi) of the copy.
  void size_for(const std::vector<std::uint32_t> &index, unsigned history) {
    index_ = &index;
    const std::size_t n = index.size();
    for (auto *c : {&x,  &y,  &z,  &vx, &vy, &vz,      &wx, &wy, &wz, &r,   &m,   &fx,
                    &fy, &fz, &tx, &ty, &tz, &overlap, &nx, &ny, &nz, &wvx, &wvy, &wvz})
      c->resize(n);
    history_ = history;
    wall_hist.resize(n * history);
  }
  void gather(const ParticleArrays<Real> &p, const std::vector<Real> &hist, std::size_t lo, std::size_t hi) {
    const std::uint32_t *idx = index_->data();
    const unsigned history = history_;
    for (std::size_t q = lo; q < hi; ++q) {
      const std::uint32_t i = idx[q];
      x[q] = p.x[i];
      y[q] = p.y[i];
      z[q] = p.z[i];
      vx[q] = p.vx[i];
      vy[q] = p.vy[i];
      vz[q] = p.vz[i];
      wx[q] = p.wx[i];
      wy[q] = p.wy[i];
      wz[q] = p.wz[i];
      r[q] = p.r[i];
      m[q] = p.m[i];
      fx[q] = 0;
      fy[q] = 0;
      fz[q] = 0;
      tx[q] = 0;
      ty[q] = 0;
      tz[q] = 0;
      overlap[q] = 0;
      for (unsigned h = 0; h < history; ++h) wall_hist[q * history + h] = hist[std::size_t(i) * history + h];
    }
  }

  // The wall records of a plane: its overlap with each particle, one normal and one velocity.
  void plane_records(const std::vector<Real> &dense_overlap, const Real normal[3], const Real velocity[3]) {
    const std::uint32_t *idx = index_->data();
    for (std::size_t q = 0; q < x.size(); ++q) {
      overlap[q] = dense_overlap[idx[q]];
      nx[q] = normal[0];
      ny[q] = normal[1];
      nz[q] = normal[2];
      wvx[q] = velocity[0];
      wvy[q] = velocity[1];
      wvz[q] = velocity[2];
    }
  }

  // The copy as the plugins see it; `like` gives the domain, dt and time.
  Particles<Real> particles(const Particles<Real> &like) {
    Particles<Real> v = like;
    v.n = static_cast<std::uint32_t>(x.size());
    v.x = x.data();
    v.y = y.data();
    v.z = z.data();
    v.vx = vx.data();
    v.vy = vy.data();
    v.vz = vz.data();
    v.wx = wx.data();
    v.wy = wy.data();
    v.wz = wz.data();
    v.r = r.data();
    v.m = m.data();
    v.fx = fx.data();
    v.fy = fy.data();
    v.fz = fz.data();
    v.tx = tx.data();
    v.ty = ty.data();
    v.tz = tz.data();
    return v;
  }
  WallContacts<Real> walls() {
    return {static_cast<std::uint32_t>(x.size()),
            overlap.data(),
            nx.data(),
            ny.data(),
            nz.data(),
            wvx.data(),
            wvy.data(),
            wvz.data(),
            wall_hist.data()};
  }

  // Adds the copy's forces and torques to the particles, and writes back their wall overlap and history
  // (of the whole copy, or of its part [lo, hi)).
  void scatter(ParticleArrays<Real> &p, std::vector<Real> &dense_overlap, std::vector<Real> &hist) const {
    parallel_for(
        this_thread_team(), x.size(),
        [&](long long q) { scatter(p, dense_overlap, hist, std::size_t(q), std::size_t(q) + 1); },
        x.size() > parallel_from);
  }
  void scatter(ParticleArrays<Real> &p, std::vector<Real> &dense_overlap, std::vector<Real> &hist, std::size_t lo,
               std::size_t hi) const {
    const std::uint32_t *idx = index_->data();
    const unsigned history = history_;
    for (std::size_t q = lo; q < hi; ++q) {
      const std::uint32_t i = idx[q];
      p.fx[i] += fx[q];
      p.fy[i] += fy[q];
      p.fz[i] += fz[q];
      p.tx[i] += tx[q];
      p.ty[i] += ty[q];
      p.tz[i] += tz[q];
      dense_overlap[i] = overlap[q];
      for (unsigned h = 0; h < history; ++h) hist[std::size_t(i) * history + h] = wall_hist[q * history + h];
    }
  }

 private:
  std::vector<Real> x, y, z, vx, vy, vz, wx, wy, wz, r, m, fx, fy, fz, tx, ty, tz;
  std::vector<Real> overlap, nx, ny, nz, wvx, wvy, wvz, wall_hist;
  const std::vector<std::uint32_t> *index_ = nullptr;
  unsigned history_ = 0;
};

}  // namespace spreadmap::engine
