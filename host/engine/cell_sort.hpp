// Particles sorted into the cells of a CellGrid by a stable counting sort (the particles of one cell
// keep their order): the first step of every neighbour-list build, after which the particle arrays
// are gathered into the sorted order and each cell's particles lie together.
#pragma once
#include <engine/cell_grid.hpp>
#include <engine/thread_team.hpp>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace spreadmap::engine {

struct CellSort {
  std::vector<std::uint32_t> cell;    // the cell of each particle, in the particles' order
  std::vector<std::uint32_t> start;   // the first slot of each cell, and one past the last: count() + 1
  std::vector<std::uint32_t> order;   // the particle in each slot
  std::vector<std::uint32_t> sorted;  // the cell of each slot
  std::vector<std::uint32_t> next;    // the next free slot of each cell while sorting

  template <class Real> void sort(const CellGrid<Real> &grid, const Real *x, const Real *y, const Real *z, std::size_t n) {
    cell.resize(n);
    parallel_for(this_thread_team(), n, [&](long long i) { cell[i] = grid.cell_of(x[i], y[i], z[i]); });
    const std::size_t cells = grid.count();
    start.assign(cells + 1, 0);
    for (std::size_t i = 0; i < n; ++i) ++start[cell[i] + 1];
    for (std::size_t c = 0; c < cells; ++c) start[c + 1] += start[c];
    order.resize(n);
    sorted.resize(n);
    next.assign(start.begin(), start.end() - 1);
    for (std::size_t i = 0; i < n; ++i) {
      const std::uint32_t slot = next[cell[i]]++;
      order[slot] = static_cast<std::uint32_t>(i);
      sorted[slot] = cell[i];
    }
  }
  // Whether every particle stays where it was (no gather needed).
  bool unmoved() const {
    for (std::size_t i = 0; i < order.size(); ++i)
      if (order[i] != i) return false;
    return true;
  }
};

}  // namespace spreadmap::engine
