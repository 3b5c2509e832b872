// Full (both-direction) Verlet list in CSR form over cell-sorted particles, with contact history
// carried from the previous list by particle identity, and optionally each entry's mirror.
//
// Determinism: the neighbours of i are listed in a fixed order (neighbour cells in a fixed order,
// particles within a cell by index), a function of the state only; threads build contiguous
// blocks of particles that are concatenated in particle order, so the list is the same for any
// thread count.
#pragma once
#include <engine/cell_grid.hpp>
#include <engine/pair_loops.hpp>
#include <engine/particle_arrays.hpp>
#include <spreadmap/batch.hpp>

#include <cstdint>
#include <vector>

namespace spreadmap::engine {

template <class Real> class NeighbourList {
 public:
  // p must be sorted by cell: cell_start[c] .. cell_start[c + 1] are the particles of cell c and
  // cell[i] is the cell of particle i. p.list_index[i] is i's index in the previous list (no_index
  // for particles it did not know); history values of pairs present in both lists are copied, new
  // pairs start at zero. Lists j when |x_i - x_j| < r_i + r_j + skin (minimum image).
  // with_mirror: also find each entry's mirror (the entry (j, i) of (i, j)) and size the scratch of
  // the CPU loop that evaluates each pair once (laws without history, or whose history mirrors: see
  // law_pairs_once and engine/pair_loops.hpp).
  void build(const ParticleArrays<Real> &p, const CellGrid<Real> &grid, const std::vector<std::uint32_t> &cell_start,
             const std::vector<std::uint32_t> &cell, const Domain &domain, Real skin, unsigned history,
             bool with_mirror = false, const Real *mobile = nullptr);

  ListView<Real> view() {
    const bool once = has_mirror_ && !nbr.empty();
    if (!once) return {start.data(), nbr.data(), hist.data()};
    return {start.data(), nbr.data(),    hist.data(),     mirror.data(),     scratch.data(),
            upper.data(), pair_i.data(), pair_j.data(),   first_pair.data(), pair_entry.data(),
            &balance_,    packed(),      in_reach_.data()};
  }
  std::size_t entries() const { return nbr.size(); }
  // The particles whose pairs each of `threads` threads evaluates in the pair loop of pair_loops.hpp
  // (thread t: [cuts[t], cuts[t + 1])), when that loop is used; false otherwise.
  bool pair_owners(int threads, std::vector<std::size_t> &cuts) const;
  // After start/nbr were replaced (a checkpoint): finds the mirrors again when asked.
  void restore_mirror(bool with_mirror) {
    has_mirror_ = false;
    if (with_mirror && !nbr.empty()) find_mirrors();
  }
  void clear() {
    start.clear();
    nbr.clear();
    hist.clear();
    has_mirror_ = false;
  }

  // The list itself (public for checkpoints).
  std::vector<std::uint32_t> start, nbr;
  std::vector<Real> hist;

 private:
  void find_mirrors();

  // Mirror entries, each particle's first upper entry, the upper entries as a flat sequence (with
  // their entries), and the pair loop's scratch (a record of 6 values per entry, then 6 running sums
  // per particle).
  std::vector<std::uint32_t> mirror, upper, pair_i, pair_j, first_pair, pair_entry;
  std::vector<Real> scratch;
  // Room for the pair loop's packed spheres (x, y, z, r: 4 values a particle), 32 bytes aligned from packed().
  std::vector<Real> packed_;
  Real *packed() {
    const auto at = reinterpret_cast<std::uintptr_t>(packed_.data());
    return reinterpret_cast<Real *>((at + 31) & ~std::uintptr_t(31));
  }
  // Each upper pair within the law's reach at its last filter (ListView::in_reach): 1 for all after a
  // build for a law with history, and after a restore (which does not know the law).
  std::vector<std::uint8_t> in_reach_;
  PairBalance balance_{};
  bool has_mirror_ = false;
  std::vector<std::uint32_t> old_start_, old_nbr_, lower_;
  std::vector<Real> old_hist_;
  std::vector<std::vector<std::uint32_t>> thread_nbr_;
  std::vector<std::size_t> thread_first_;  // each thread's first particle in the last build
};

}  // namespace spreadmap::engine
