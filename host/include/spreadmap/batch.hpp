// Structure-of-arrays views the engine hands to plugin loops, one call per step per batch.
// Plain standard-layout structs (safe across the C boundary); pointers are host memory on the CPU
// backend and device memory on the CUDA backend. The engine owns every array.
#pragma once
#include <cstdint>

namespace spreadmap {

struct Team;  // team.hpp

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
  const Team *team = nullptr;  // the host's threads, for the loop to run on (null: an OpenMP region)
};

// How the threads of the pair loop share its list entries, tuned by the loop from how long each
// thread took: the split decides which thread evaluates a pair, never the result (pair_once.hpp).
// Engine-owned, zero at first.
struct PairBalance {
  static constexpr int max_threads = 64;
  std::int32_t threads;         // cut is for this many threads (otherwise equal shares)
  double cut[max_threads + 1];  // thread t takes the entries from cut[t] to cut[t + 1] x all
  double seconds[max_threads];  // each thread's last sweep
};

// Full (both-direction) neighbour list in CSR form: the neighbours of particle i are
// nbr[start[i] .. start[i+1]), in increasing index order. Each particle sums its own forces in this
// fixed order, so results do not depend on the number of threads. hist holds `history` values per
// list entry; the engine carries them across list rebuilds.
// Optional (null when absent), for laws without history on the CPU (pair_once.hpp): mirror[k] is
// the entry (j, i) of entry k = (i, j); upper[i] is particle i's first entry with j > i. The upper
// entries of all particles, in list order, also stand as one flat sequence: pair u is (pair_i[u],
// pair_j[u]), and particle i's are pairs [first_pair[i], first_pair[i + 1]). scratch holds
// 6 * (entries + particles) values: a record of 6 values per entry, then 6 running sums per
// particle; all of it must be zero on entry, and the loop leaves it zero on exit. balance: see
// PairBalance above.
template <class Real> struct PairList {
  const std::uint32_t *start;
  const std::uint32_t *nbr;
  Real *hist;
  const std::uint32_t *mirror = nullptr;
  Real *scratch = nullptr;
  const std::uint32_t *upper = nullptr;
  const std::uint32_t *pair_i = nullptr, *pair_j = nullptr, *first_pair = nullptr;
  PairBalance *balance = nullptr;  // null: equal shares of the entries
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

}  // namespace spreadmap
