// The sort of particles into the list's cells (engine/cell_sort.hpp): a stable counting sort, so
// each cell's particles lie together, in their old order, and the cells in increasing index.
#include <gtest/gtest.h>

#include <engine/cell_sort.hpp>

#include <random>
#include <vector>

namespace se = spreadmap::engine;

TEST(CellSort, EachCellHoldsItsParticlesTogetherInTheirOldOrder) {
  se::CellGrid<double> grid;
  grid.n[0] = 4, grid.n[1] = 3, grid.n[2] = 5;
  for (int a = 0; a < 3; ++a) grid.inv_size[a] = 1.0;  // unit cells from the origin
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-0.5, 5.5);  // some outside: clamped to the border cells
  const std::size_t n = 500;
  std::vector<double> x(n), y(n), z(n);
  for (std::size_t i = 0; i < n; ++i) x[i] = u(rng), y[i] = u(rng), z[i] = u(rng);
  se::CellSort s;
  s.sort(grid, x.data(), y.data(), z.data(), n);
  ASSERT_EQ(s.start.size(), grid.count() + 1);
  EXPECT_EQ(s.start.front(), 0u);
  EXPECT_EQ(s.start.back(), n);
  std::vector<int> seen(n, 0);
  for (std::size_t c = 0; c < grid.count(); ++c)
    for (std::uint32_t k = s.start[c]; k < s.start[c + 1]; ++k) {
      const std::uint32_t i = s.order[k];
      ++seen[i];
      EXPECT_EQ(grid.cell_of(x[i], y[i], z[i]), c) << "particle " << i;
      EXPECT_EQ(s.sorted[k], c);
      if (k > s.start[c]) {
        EXPECT_LT(s.order[k - 1], i) << "stable: a cell keeps its particles' order";
      }
    }
  for (std::size_t i = 0; i < n; ++i) EXPECT_EQ(seen[i], 1) << "particle " << i << " in exactly one slot";
  EXPECT_FALSE(s.unmoved());
  // Sorted once, the particles sort onto themselves.
  std::vector<double> xs(n), ys(n), zs(n);
  for (std::size_t k = 0; k < n; ++k) xs[k] = x[s.order[k]], ys[k] = y[s.order[k]], zs[k] = z[s.order[k]];
  s.sort(grid, xs.data(), ys.data(), zs.data(), n);
  EXPECT_TRUE(s.unmoved());
}
