// The engine's CPU calls into contact laws and geometries: it walks the lists and records and shares
// them between its threads itself, handing a plugin queues of contacts (a law) or ranges of particles
// (a geometry), one call each (spreadmap/batch.hpp, ABI 10.3). A plugin built for an older minor gets
// its whole-list call instead, with no schedule in it: it evaluates every entry, which gives the same
// bits, on the calling thread or in its own OpenMP region.
#pragma once
#include <engine/pair_loops.hpp>
#include <engine/walls.hpp>
#include <spreadmap/batch.hpp>

namespace spreadmap::engine {

// Whether the CPU pair loop may evaluate each touching pair once for this law (engine/pair_loops.hpp):
// it keeps no history, or (ABI 10.4) every value it keeps mirrors, the other body's the negation, and
// its queues have room for them.
inline bool law_pairs_once(const ContactLaw &law) {
  const std::uint32_t history = law_history(law);
  if (history == 0) return true;
  return law.abi_minor >= 4 && law.ops->history_mirrors && law.ops->history_mirrors(law.self) != 0 &&
         history <= detail::queued_history_max;
}

// Adds the forces of every pair of `list` within the law's reach to p's accumulators; runs `side` once,
// beside them where the loop can (pair_forces_once), else after them.
template <class Real>
void pair_forces(const ContactLaw &law, const Particles<Real> &p, const ListView<Real> &list, PairSideJob side = {});

// Adds the forces of one wall's records w (interacting: overlap above -w.gap and the law's range, or
// touching) to p's accumulators; a record apart clears its history.
template <class Real> void wall_forces(const ContactLaw &law, const Particles<Real> &p, const WallContacts<Real> &w);

// Fills the wall records w of every particle of p for a geometry at time p.t.
template <class Real>
void geometry_contacts(const GeometryWall &geometry, const Particles<Real> &p, WallContacts<Real> &w);

// For a caller that shares the records between its threads itself (a geometry's copy, evaluated in the
// pair loop's run by the threads that own its particles): whether the plugins take ranges (ABI 10.3;
// an older one takes only its whole-list call), and the two calls above over records [lo, hi) alone,
// on the calling thread.
inline bool takes_ranges(const ContactLaw &law) { return law.abi_minor >= 3; }
inline bool takes_ranges(const GeometryWall &geometry) { return geometry.abi_minor >= 3; }
template <class Real>
void wall_forces_range(const ContactLaw &law, const Particles<Real> &p, const WallContacts<Real> &w, std::uint32_t lo,
                       std::uint32_t hi);
template <class Real>
void geometry_contacts_range(const GeometryWall &geometry, const Particles<Real> &p, WallContacts<Real> &w,
                             std::uint32_t lo, std::uint32_t hi);

}  // namespace spreadmap::engine
