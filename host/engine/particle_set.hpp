// ParticleSet: the plain exchange format between the engine, files and other stages. One entry per
// particle in every non-empty column, SI units. Optional columns may be empty (meaning zero, or for
// `mass`, "derive from a density"; for `id`, "number them").
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace spreadmap::engine {

struct ParticleSet {
  std::vector<double> x, y, z;     // centre [m]
  std::vector<double> vx, vy, vz;  // velocity [m/s]         (optional)
  std::vector<double> wx, wy, wz;  // angular velocity [rad/s] (optional)
  std::vector<double> radius;      // [m]
  std::vector<double> mass;        // [kg]                   (optional)
  std::vector<std::uint32_t> id;   // stable identity         (optional)
  // 1: the particle never moves (zero velocity, not integrated; an infinite mass to the particles
  // it touches). Optional: empty means none is fixed.
  std::vector<std::uint8_t> fixed;

  std::size_t size() const { return x.size(); }
  // Throws SetupError naming the first column whose length differs from x (empty optional columns
  // are fine) or the first non-finite / non-positive value where one is not allowed. `what` names
  // the source in the message (a file, "add_particles").
  void validate(const std::string &what) const;
  // Fills empty optional columns: zeros for velocities, ids first_id, first_id + 1, ... ; masses
  // from `density` when density > 0.
  void fill_defaults(double density, std::uint32_t first_id);
  // x, y, z, vx, vy, vz, wx, wy, wz of every particle, in id order: two states compare bitwise
  // whatever order their engines keep the particles in.
  std::vector<double> kinematics_by_id() const;
};

// The particles i of `set` for which keep(i) holds, in their order, every column kept (an optional
// column left empty stays empty).
template <class Keep> ParticleSet select_particles(const ParticleSet &set, Keep keep) {
  ParticleSet out;
  auto copy = [&](const auto &from, auto &to, std::size_t i) {
    if (!from.empty()) to.push_back(from[i]);
  };
  for (std::size_t i = 0; i < set.size(); ++i) {
    if (!keep(i)) continue;
    for (auto column : {&ParticleSet::x, &ParticleSet::y, &ParticleSet::z, &ParticleSet::vx, &ParticleSet::vy,
                        &ParticleSet::vz, &ParticleSet::wx, &ParticleSet::wy, &ParticleSet::wz, &ParticleSet::radius,
                        &ParticleSet::mass})
      copy(set.*column, out.*column, i);
    copy(set.id, out.id, i);
    copy(set.fixed, out.fixed, i);
  }
  return out;
}

}  // namespace spreadmap::engine
