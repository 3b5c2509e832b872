// What the engine calls for contacts: bound contact-law instances and walls. A law is a plugin's
// ops table plus one bound instance (`self`); the same plugin bound twice (particle-particle,
// particle-substrate, particle-spreader) is how per-pair materials work. The engine never owns
// `self`: the caller keeps the plugin instances alive for the life of the Simulation.
#pragma once
#include <spreadmap/contact.hpp>
#include <spreadmap/geometry.hpp>

#include <array>
#include <cstdint>
#include <string>

namespace spreadmap::engine {

// abi_minor: the plugin ABI minor version its ops table was built for, which says which fields it has
// (a table from this program's own SDK headers has them all).
struct ContactLaw {
  const sm_contact_ops_v1 *ops = nullptr;
  const void *self = nullptr;
  std::uint32_t abi_minor = SPREADMAP_PLUGIN_ABI_MINOR;
};

// How far across a gap a bound law attracts [m]; 0: touching contacts only.
inline double law_range(const ContactLaw &law) { return law.ops && law.ops->range ? law.ops->range(law.self) : 0; }

// History values per contact of this bound instance (ABI 10.1; before it, the table's one count).
inline std::uint32_t law_history(const ContactLaw &law) {
  if (!law.ops) return 0;
  return law.abi_minor >= 1 && law.ops->history_of ? law.ops->history_of(law.self) : law.ops->history;
}

// An infinite plane. Particles on the side `normal` points to touch it when closer than their
// radius. The point moves with `velocity` (a tangential velocity is a conveyor: the plane stays put
// but drags particles through friction). Inactive walls exert nothing and keep no history.
struct PlaneWall {
  std::array<double, 3> point{0, 0, 0};     // [m]
  std::array<double, 3> normal{0, 0, 1};    // unit (normalised on add), into the particle side
  std::array<double, 3> velocity{0, 0, 0};  // [m/s]
  ContactLaw law;
  bool active = true;
  std::string name = "plane";  // for messages
};

// How deep a sphere (centre x, y, z, radius r) sinks into a plane through p with unit normal n:
// > 0 touching. Host-device: both backends' plane contacts.
template <class Real> SM_HD Real plane_overlap(const Real p[3], const Real n[3], Real x, Real y, Real z, Real r) {
  return r - ((x - p[0]) * n[0] + (y - p[1]) * n[1] + (z - p[2]) * n[2]);
}

// The overlaps of particles [lo, hi) with a plane into `overlap`, `floor` where not above it (0 for a
// law of touching contacts, -range for one that attracts across a gap); returns how many are above.
// One loop without a branch: it vectorises.
template <class Real>
std::uint32_t plane_overlaps(const Real p[3], const Real n[3], const Real *x, const Real *y, const Real *z,
                             const Real *r, Real *overlap, std::size_t lo, std::size_t hi, Real floor) {
  std::uint32_t touching = 0;
#pragma GCC ivdep
  for (std::size_t i = lo; i < hi; ++i) {
    const Real o = plane_overlap(p, n, x[i], y[i], z[i], r[i]);
    overlap[i] = o > floor ? o : floor;
    touching += o > floor ? 1u : 0u;
  }
  return touching;
}

// A geometry plugin (spreader, substrate shape) producing wall contacts each step. It sees the
// simulation's time plus time_shift: a spreader rests for t < 0, so a heap settles beside one
// shifted far enough back.
struct GeometryWall {
  const sm_spreader_ops_v2 *ops = nullptr;
  const void *self = nullptr;
  ContactLaw law;
  std::string name = "geometry";  // for messages: the plugin's kind/name
  double time_shift = 0;          // [s]
  std::uint32_t abi_minor = SPREADMAP_PLUGIN_ABI_MINOR;  // of the plugin (before 10.3: its whole-list call)
};

}  // namespace spreadmap::engine
