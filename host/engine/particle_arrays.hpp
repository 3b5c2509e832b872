// Structure-of-arrays particle state of one Simulation. Every per-particle column lives here so
// that sorting by cell and removing particles are one gather over all of them.
#pragma once
#include <engine/thread_team.hpp>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace spreadmap::engine {

inline constexpr std::uint32_t no_index = 0xffffffffu;

template <class Real> struct ParticleArrays {
  std::vector<Real> x, y, z, vx, vy, vz, wx, wy, wz;  // state
  std::vector<Real> r, m, inv_m, inv_i;               // radius, mass, 1/m, 1/(2/5 m r^2)
  std::vector<Real> fx, fy, fz, tx, ty, tz;           // force and torque of the last evaluation
  std::vector<Real> x0, y0, z0;                       // positions at the last list build
  std::vector<std::uint32_t> id;                      // stable identity
  std::vector<std::uint32_t> list_index;              // index in the current list, no_index if new
  std::vector<Real> mobile;                           // 1 integrated, 0 asleep (Settings::sleep)
  std::vector<std::uint32_t> calm;                    // checks in a row at rest (Settings::sleep)

  std::size_t size() const { return x.size(); }

  template <class F> void for_each_real(F &&f) {
    for (auto *c : {&x,     &y,  &z,  &vx, &vy, &vz, &wx, &wy, &wz, &r,  &m,     &inv_m,
                    &inv_i, &fx, &fy, &fz, &tx, &ty, &tz, &x0, &y0, &z0, &mobile})
      f(*c);
  }
  template <class F> void for_each_index(F &&f) {
    f(id);
    f(list_index);
    f(calm);
  }
  void resize(std::size_t n) {
    for_each_real([n](std::vector<Real> &c) { c.resize(n, Real(0)); });
    for_each_index([n](std::vector<std::uint32_t> &c) { c.resize(n, no_index); });
  }
};

// new[i] = old[src[i]] (stride values per particle) for one column. The scratch buffer and the
// column swap storage, so once both have grown to the largest size nothing is allocated again.
template <class T>
void gather(std::vector<T> &column, const std::vector<std::uint32_t> &src, std::vector<T> &scratch,
            std::size_t stride = 1) {
  const std::size_t n = src.size();
  scratch.resize(n * stride);
  T *out = scratch.data();
  const T *in = column.data();
  parallel_for(this_thread_team(), n, [&](long long ii) {
    const std::size_t i = static_cast<std::size_t>(ii), s = src[i];
    for (std::size_t q = 0; q < stride; ++q) out[i * stride + q] = in[s * stride + q];
  });
  column.swap(scratch);
}

}  // namespace spreadmap::engine
