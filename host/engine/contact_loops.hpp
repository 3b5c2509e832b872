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

// Adds the forces of every pair of `list` within the law's reach to p's accumulators.
template <class Real> void pair_forces(const ContactLaw &law, const Particles<Real> &p, const ListView<Real> &list);

// Adds the forces of one wall's records w (interacting: overlap above -w.gap and the law's range, or
// touching) to p's accumulators; a record apart clears its history.
template <class Real> void wall_forces(const ContactLaw &law, const Particles<Real> &p, const WallContacts<Real> &w);

// Fills the wall records w of every particle of p for a geometry at time p.t.
template <class Real> void geometry_contacts(const GeometryWall &geometry, const Particles<Real> &p, WallContacts<Real> &w);

}  // namespace spreadmap::engine
