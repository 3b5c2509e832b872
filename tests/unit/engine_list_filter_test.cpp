// The list build's search of four candidates at a time (engine/list_filter.hpp) lists the neighbours
// the scalar search (list_neighbours) lists, in the same order: across every periodic axis, at
// separations of exactly half a period, exactly at the reach, with ranges of every length and a
// first index inside a range; and joining touching ranges keeps the particles and their order.
#include <engine/list_filter.hpp>
#include <engine/neighbour_listing.hpp>
#include <spreadmap/simd.hpp>

#include <algorithm>
#include <cstdint>
#include <gtest/gtest.h>
#include <random>
#include <vector>

namespace sm = spreadmap;
using namespace sm::engine;

namespace {

// Every particle of `ranges`, in the order a search meets them.
std::vector<std::uint32_t> members(const CellRanges &ranges) {
  std::vector<std::uint32_t> all;
  for (int q = 0; q < ranges.n; ++q)
    for (std::uint32_t j = ranges.begin[q]; j < ranges.end[q]; ++j) all.push_back(j);
  return all;
}

TEST(EngineListFilter, JoiningTouchingRangesKeepsTheParticlesAndTheirOrder) {
  CellRanges r;
  const std::uint32_t begin[] = {0, 3, 3, 9, 12, 20, 21}, end[] = {3, 3, 7, 12, 15, 21, 30};
  r.n = 7;
  for (int q = 0; q < r.n; ++q) r.begin[q] = begin[q], r.end[q] = end[q];
  const std::vector<std::uint32_t> before = members(r);
  join_touching(r);
  EXPECT_EQ(members(r), before);
  ASSERT_EQ(r.n, 3) << "[0, 7), [9, 15), [20, 30)";
  EXPECT_EQ(r.begin[0], 0u);
  EXPECT_EQ(r.end[0], 7u);
  EXPECT_EQ(r.begin[1], 9u);
  EXPECT_EQ(r.end[1], 15u);
  EXPECT_EQ(r.begin[2], 20u);
  EXPECT_EQ(r.end[2], 30u);
  CellRanges none;
  join_touching(none);
  EXPECT_EQ(none.n, 0);
}

TEST(EngineListFilter, RowRunsHoldTheParticlesOfTheNeighbourCellsInTheirOrder) {
  std::mt19937_64 random(3);
  const int orders[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};  // fastest first
  int grids = 0;
  for (int nx = 1; nx <= 4; ++nx)
    for (int ny = 1; ny <= 3; ++ny)
      for (int nz : {1, 2, 5})
        for (int periodic = 0; periodic < 8; ++periodic)
          for (const auto &order : orders) {
            CellGrid<double> grid;
            grid.n[0] = nx, grid.n[1] = ny, grid.n[2] = nz;
            for (int a = 0; a < 3; ++a) grid.periodic[a] = (periodic >> a & 1) != 0;
            for (int a = 0; a < 3; ++a) grid.order[a] = order[a];
            // 0 to 3 particles a cell, about a quarter of the cells empty
            std::vector<std::uint32_t> cell_start{0};
            for (std::size_t c = 0; c < grid.count(); ++c) cell_start.push_back(cell_start.back() + random() % 4);
            for (std::uint32_t cell = 0; cell < grid.count(); ++cell) {
              CellRanges cells = neighbour_ranges(grid, cell, cell_start.data());
              join_touching(cells);
              const CellRanges runs = neighbour_runs(grid, cell, cell_start.data());
              ASSERT_EQ(members(runs), members(cells))
                  << "grid " << nx << "x" << ny << "x" << nz << ", periodic " << periodic << ", fastest axis "
                  << order[0] << ", cell " << cell;
              EXPECT_EQ(runs.n, cells.n) << "both joined";
            }
            ++grids;
          }
  EXPECT_EQ(grids, 4 * 3 * 3 * 8 * 6);
}

#if SPREADMAP_SIMD_LEVELS
// Spheres in a box, with pairs placed on the search's edges right after particle 0.
struct Spheres {
  std::vector<double> x, y, z, r;
  double length[3] = {1.0, 0.75, 0.5};
  double skin = 0.015625;

  Spheres() {
    // particle 0 and, from 1 (values exact in binary): exactly half a period away along each axis
    // (both images equally far; within reach), exactly at the reach (not listed) inside the box and
    // across x's boundary, and just inside the reach
    auto add = [&](double px, double py, double pz, double pr) {
      x.push_back(px), y.push_back(py), z.push_back(pz), r.push_back(pr);
    };
    add(0.75, 0.125, 0.125, 0.25);
    add(0.25, 0.125, 0.125, 0.25);       // 1: dx = L/2
    add(0.75, 0.5, 0.125, 0.125);        // 2: dy = -L/2
    add(0.75, 0.125, 0.375, 0.125);      // 3: dz = -L/2
    add(0.359375, 0.125, 0.125, 0.125);  // 4: dx = 0.390625, the reach: not listed
    add(0.140625, 0.125, 0.125, 0.125);  // 5: the same across x's boundary
    add(0.375, 0.125, 0.125, 0.125);     // 6: just inside
    std::mt19937_64 random(7);
    std::uniform_real_distribution<double> unit(0, 1), size(0.02, 0.15);
    while (x.size() < 300)
      add(unit(random) * length[0], unit(random) * length[1], unit(random) * length[2], size(random));
  }
};

template <bool PX, bool PY, bool PZ> void expect_same_as_scalar() {
  ASSERT_GE(sm::simd_supported(), sm::SimdLevel::avx2) << "the search needs AVX2 (x86-64-v3)";
  const Spheres s;
  const bool per[3] = {PX, PY, PZ};
  const auto n = std::uint32_t(s.x.size());
  std::mt19937_64 random(11);
  std::size_t listed = 0, candidates = 0;
  for (std::uint32_t i = 0; i + 1 < n; ++i) {
    // runs of 0 to 12 particles with gaps between them, from below i to the end
    CellRanges ranges;
    std::uint32_t at = i > 5 ? i - 5 : 0;
    if (i == 0) ranges.begin[0] = 0, ranges.end[0] = 7, ranges.n = 1, at = 9;  // the placed pairs
    while (at < n && ranges.n < 27) {
      const std::uint32_t length = std::uint32_t(random() % 13), end = std::min(n, at + length);
      ranges.begin[ranges.n] = at, ranges.end[ranges.n] = end, ++ranges.n;
      at = end + std::uint32_t(random() % 4);
    }
    std::vector<std::uint32_t> plain(n + 4), fast(n + 4);
    const std::uint32_t above = i + 1;
    const std::uint32_t a =
        list_neighbours(i, s.x.data(), s.y.data(), s.z.data(), s.r.data(), static_cast<const double *>(nullptr),
                        s.length, per, s.skin, ranges, plain.data(), n, above);
    const std::uint32_t b = list_neighbours_four<PX, PY, PZ>(i, s.x.data(), s.y.data(), s.z.data(), s.r.data(),
                                                             s.length, s.skin, ranges, fast.data(), above);
    ASSERT_EQ(a, b) << "particle " << i;
    plain.resize(a), fast.resize(b);
    EXPECT_EQ(fast, plain) << "particle " << i;
    listed += a;
    for (int q = 0; q < ranges.n; ++q)
      candidates += ranges.end[q] > above ? ranges.end[q] - std::max(ranges.begin[q], above) : 0;
    if (i == 0 && PX && PY && PZ) {
      std::vector<std::uint32_t> placed;
      for (const std::uint32_t j : plain)
        if (j < 7) placed.push_back(j);
      EXPECT_EQ(placed, (std::vector<std::uint32_t>{1, 2, 3, 6}))
          << "the half-period images and the sphere just inside are listed, those exactly at the reach not";
    }
  }
  EXPECT_GT(listed, 100u);
  EXPECT_GT(candidates - listed, 100u);
}

TEST(EngineListFilter, FourAtATimeListsTheScalarSearchsNeighbours) {
  expect_same_as_scalar<false, false, false>();
  expect_same_as_scalar<true, false, true>();
  expect_same_as_scalar<false, true, false>();
}

TEST(EngineListFilter, FourAtATimeListsTheScalarSearchsNeighboursAcrossEveryPeriodicAxis) {
  expect_same_as_scalar<true, true, true>();
}
#endif

}  // namespace
