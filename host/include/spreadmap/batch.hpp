// Structure-of-arrays views the engine hands to plugin loops, and the queues of contacts it hands to a
// law (ABI 10.3). Plain standard-layout structs (safe across the C boundary); pointers are host memory
// on the CPU backend and device memory on the CUDA backend. The engine owns every array.
//
// How the work is shared between threads is the engine's alone: it walks the list, finds the pairs
// within reach and hands a law queues of them, one call per queue (contact.hpp). No field here says how
// the engine schedules its loops, so tuning them changes no struct a plugin reads.
#pragma once
#include <cstdint>

namespace spreadmap {

// Particle state. Read-only for plugins except the force/torque accumulators.
template <class Real> struct Particles {
  std::uint32_t n;
  const Real *x, *y, *z;       // position [m]
  const Real *vx, *vy, *vz;    // velocity [m/s]
  const Real *wx, *wy, *wz;    // angular velocity [rad/s]
  const Real *r;               // radius [m]
  const Real *m;               // mass [kg]
  Real *fx, *fy, *fz;          // force accumulators [N]   (a plugin adds; never overwrites)
  Real *tx, *ty, *tz;          // torque accumulators [N m]
  Real box_lo[3], box_hi[3];   // domain
  std::uint8_t periodic[3];    // 1: periodic along that axis (minimum image)
  Real dt;                     // time step [s]
  Real t;                      // time at which forces are evaluated [s]
  const void *legacy_team = nullptr;  // ABI 10.0-10.2: the host's threads; always null since 10.3
};

// Full (both-direction) neighbour list in CSR form: the neighbours of particle i are
// nbr[start[i] .. start[i+1]), in increasing index order. Each particle sums its own forces in this
// fixed order, so results do not depend on the number of threads. hist holds `history` values per
// list entry; the engine carries them across list rebuilds. The whole-list loops read it (the CUDA
// kernels, and the CPU tables of older hosts).
template <class Real> struct PairList {
  const std::uint32_t *start;
  const std::uint32_t *nbr;
  Real *hist;
  // ABI 10.0-10.2: the CPU loop's schedule (mirror, scratch, upper, flat pairs, balance). Always null
  // since 10.3, so that an older plugin takes its loop over every entry, which gives the same bits.
  const void *legacy[7] = {};
};

// One wall contact per particle and wall, stored densely by particle index: particle i touches the
// wall when overlap[i] > 0; the records also hold gaps down to overlap = -gap (a law reaching across a
// gap attracts there; gap 0: touching records only, any other value reads as apart). normal points from the wall into
// the particle; (vx, vy, vz) is the wall's surface velocity at the contact point. hist holds `history` values per
// particle for this wall.
template <class Real> struct WallContacts {
  std::uint32_t n;
  Real *overlap;
  Real *nx, *ny, *nz;
  Real *vx, *vy, *vz;
  Real *hist;
  Real gap = 0;  // [m]
};

// ABI 10.3. A queue of pairs within the law's reach, in the order the engine adds their forces. Pair q
// is (i[q], j[q]) with d = (dx, dy, dz)[q] = x_i - x_j (minimum image). The law writes the force and
// torque on i to on_i[c * stride + q] (c: force x, y, z, torque x, y, z) and, when on_j is given (each
// touching pair is queued once: laws without history, and since 10.4 laws whose history mirrors), the
// same for j from the same evaluation. A law with history finds the pair's values at hist + q * its
// history count when on_j is given (a copy in queue order, which the engine takes from the entry
// (i, j) and puts back, and keeps the entry (j, i) as its negation: contiguous, the loop vectorises),
// and at hist + entry[q] * that count otherwise (the list's own, each entry queued with its own).
template <class Real> struct PairQueue {
  std::uint32_t n, stride;
  const std::uint32_t *i, *j;
  const Real *dx, *dy, *dz;
  const std::uint32_t *entry;  // list entries (laws with history, without on_j); may be null otherwise
  Real *hist;
  Real *on_i, *on_j;
};

// ABI 10.3. A queue of particles interacting with one wall (their records in WallContacts, history at
// hist + i[q] * the law's history count): the law writes particle i[q]'s force and torque to
// out[c * stride + q].
template <class Real> struct WallQueue {
  std::uint32_t n, stride;
  const std::uint32_t *i;
  Real *out;
};

}  // namespace spreadmap
