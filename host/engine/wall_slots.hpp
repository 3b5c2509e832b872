// What a stepper keeps for each wall: the contact records of every particle (overlap, normal,
// surface velocity), the wall law's history, and, per kind of wall, what the CPU step reuses between
// steps. Columns hold one value (history: `history` values) per particle, in the particles' order.
#pragma once
#include <engine/particle_subset.hpp>
#include <engine/walls.hpp>

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace spreadmap::engine {

template <class Real> struct WallSlot {
  std::vector<Real> overlap, nx, ny, nz, vx, vy, vz, hist;
  unsigned history = 0;
  bool touched = false;  // some particle touched at the last evaluation
  WallContacts<Real> view(std::size_t n) {
    return {static_cast<std::uint32_t>(n),
            overlap.data(),
            nx.data(),
            ny.data(),
            nz.data(),
            vx.data(),
            vy.data(),
            vz.data(),
            hist.data()};
  }
  void resize(std::size_t n) {
    for (auto *c : {&overlap, &nx, &ny, &nz, &vx, &vy, &vz}) c->resize(n, Real(0));
    hist.resize(n * history, Real(0));
  }
};

template <class Real> struct PlaneSlot {
  PlaneWall wall;
  WallSlot<Real> slot;
  std::vector<std::uint32_t> near;  // the particles its law sees this step (CPU: plane_contacts)
  // The normal and velocity its dense records hold for every particle (CPU: dense_plane_forces),
  // and for how many particles; 0: not written.
  std::array<Real, 6> records{};
  std::size_t records_for = 0;
};

// On the CPU a geometry is evaluated only for the particles near it (`near`, ascending), found by
// asking the plugin which particles a sphere 3 skins larger would touch (find_near_geometry).
template <class Real> struct GeometrySlot {
  GeometryWall geometry;
  WallSlot<Real> slot;
  std::vector<std::uint32_t> near;
  ParticleSubset<Real> copy;  // the near particles' state, and the geometry's forces on them
  bool near_valid = false;
  double near_since = 0;  // time of the search [s]
  double speed = 0;       // bound on the speed of any surface point [m/s]
};

}  // namespace spreadmap::engine
