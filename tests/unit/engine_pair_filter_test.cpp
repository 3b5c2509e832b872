// The once loop's filter of four candidates at a time (engine/pair_filter.hpp) keeps the pairs the
// scalar filter keeps, in the same order, with the same separations to the bit: across periodic
// boundaries, at separations of exactly half a period, at exactly the reach, and across a gap.
#include <engine/minimum_image.hpp>
#include <engine/pair_filter.hpp>
#include <spreadmap/simd.hpp>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <gtest/gtest.h>
#include <random>
#include <vector>

#if SPREADMAP_SIMD_LEVELS
namespace sm = spreadmap;
using namespace sm::engine;

namespace {

// A queue as the pair loop keeps it, with room past its end for the filter's four-lane stores.
struct Queue {
  std::vector<std::uint32_t> i, j, entry, apart;
  std::vector<double> dx, dy, dz;
  int size = 0, parted = 0;
  explicit Queue(std::size_t room)
      : i(room + 4), j(room + 4), entry(room + 4), apart(room + 4), dx(room + 4), dy(room + 4), dz(room + 4) {}
  FilterQueue to() { return {i.data(), j.data(), entry.data(), dx.data(), dy.data(), dz.data()}; }
};

// Spheres in a unit box, and candidate pairs among them, some placed on the filter's edges.
struct Candidates {
  std::vector<double> x, y, z, r;
  std::vector<std::uint32_t> pair_i, pair_j, pair_entry;
  double length[3] = {1.0, 0.75, 0.5};

  Candidates() {
    std::mt19937_64 random(41);
    std::uniform_real_distribution<double> unit(0, 1), size(0.02, 0.2);
    for (int k = 0; k < 400; ++k) {
      x.push_back(unit(random) * length[0]);
      y.push_back(unit(random) * length[1]);
      z.push_back(unit(random) * length[2]);
      r.push_back(size(random));
    }
    // exactly half a period apart along each axis (no image is nearer) and overlapping, so that the
    // separation is queued and a wrap to -L/2 would show in its bits; and exactly touching (not kept)
    auto place = [&](double ax, double ay, double az, double bx, double by, double bz, double ra, double rb) {
      const auto a = std::uint32_t(x.size());
      x.insert(x.end(), {ax, bx});
      y.insert(y.end(), {ay, by});
      z.insert(z.end(), {az, bz});
      r.insert(r.end(), {ra, rb});
      add(a, a + 1);
      add(a + 1, a);
    };
    place(0.75, 0.1, 0.1, 0.25, 0.1, 0.1, 0.3, 0.3);          // dx = L/2, overlapping
    place(0.1, 0.5, 0.2, 0.1, 0.125, 0.2, 0.25, 0.25);        // dy = L/2, overlapping
    place(0.1, 0.1, 0.375, 0.1, 0.1, 0.125, 0.15, 0.15);      // dz = L/2, overlapping
    place(0.5, 0.5, 0.25, 0.5, 0.25, 0.25, 0.125, 0.125);     // exactly touching inside the box
    place(0.875, 0.5, 0.25, 0.125, 0.5, 0.25, 0.125, 0.125);  // exactly touching across x's boundary
    std::uniform_int_distribution<std::uint32_t> any(0, std::uint32_t(x.size() - 1));
    for (int k = 0; k < 1001; ++k) {
      const std::uint32_t a = any(random), b = any(random);
      if (a != b) add(a, b);
    }
  }
  void add(std::uint32_t a, std::uint32_t b) {
    pair_entry.push_back(std::uint32_t(7 * pair_i.size() + 3));
    pair_i.push_back(a);
    pair_j.push_back(b);
  }
  std::uint32_t count() const { return std::uint32_t(pair_i.size()); }
};

// The scalar filter of engine/pair_loops.hpp, candidate by candidate.
template <bool PX, bool PY, bool PZ, bool Gap, bool History>
void filter_scalar(const Candidates &c, std::uint32_t u, std::uint32_t stop, double range, Queue &q) {
  for (; u < stop; ++u) {
    const std::uint32_t i = c.pair_i[u], j = c.pair_j[u];
    const double dx = wrap_axis<PX>(c.x[i] - c.x[j], c.length[0]), dy = wrap_axis<PY>(c.y[i] - c.y[j], c.length[1]),
                 dz = wrap_axis<PZ>(c.z[i] - c.z[j], c.length[2]);
    const double reach = Gap ? c.r[i] + c.r[j] + range : c.r[i] + c.r[j];
    if (dx * dx + dy * dy + dz * dz < reach * reach) {
      q.i[q.size] = i;
      q.j[q.size] = j;
      q.entry[q.size] = c.pair_entry[u];
      q.dx[q.size] = dx;
      q.dy[q.size] = dy;
      q.dz[q.size] = dz;
      ++q.size;
    } else if (History) {
      q.apart[q.parted++] = c.pair_entry[u];
    }
  }
}

template <bool PX, bool PY, bool PZ, bool Gap, bool History> void expect_same_as_scalar(double range) {
  ASSERT_GE(sm::simd_supported(), sm::SimdLevel::avx2) << "the filter needs AVX2 (x86-64-v3)";
  const Candidates c;
  std::vector<double> storage(4 * c.x.size() + 4);
  auto *packed =
      reinterpret_cast<double *>((reinterpret_cast<std::uintptr_t>(storage.data()) + 31) & ~std::uintptr_t(31));
  sm::Particles<double> spheres{};
  spheres.n = std::uint32_t(c.x.size());
  spheres.x = c.x.data();
  spheres.y = c.y.data();
  spheres.z = c.z.data();
  spheres.r = c.r.data();
  pack_spheres(spheres, 0, spheres.n, packed);
  Queue fast(c.count()), plain(c.count());
  std::vector<std::uint8_t> in_reach(c.count(), 1);  // as after a build: every pair may hold history
  const std::uint32_t left = filter_packed<PX, PY, PZ, Gap, History>(
      packed, c.pair_i.data(), c.pair_j.data(), c.pair_entry.data(), 0, c.count(), c.length, range, fast.to(),
      fast.size, in_reach.data(), fast.apart.data(), fast.parted);
  EXPECT_EQ(left, c.count() / 4 * 4) << "it stops where fewer than four candidates remain";
  filter_scalar<PX, PY, PZ, Gap, History>(c, 0, left, range, plain);
  EXPECT_GT(plain.size, 50);
  EXPECT_GT(int(left) - plain.size, 50);
  ASSERT_EQ(fast.size, plain.size);
  if (PX && PY && PZ && !Gap) {  // the half-period pairs (both ways) are kept, the exactly touching ones not
    EXPECT_EQ(std::vector(plain.i.begin(), plain.i.begin() + 6),
              (std::vector<std::uint32_t>{400, 401, 402, 403, 404, 405}));
  }
  ASSERT_EQ(fast.parted, History ? plain.parted : 0);
  const auto n = std::size_t(plain.size);
  EXPECT_EQ(std::vector(fast.i.begin(), fast.i.begin() + n), std::vector(plain.i.begin(), plain.i.begin() + n));
  EXPECT_EQ(std::vector(fast.j.begin(), fast.j.begin() + n), std::vector(plain.j.begin(), plain.j.begin() + n));
  EXPECT_EQ(0, std::memcmp(fast.dx.data(), plain.dx.data(), n * sizeof(double))) << "dx differs in its bits";
  EXPECT_EQ(0, std::memcmp(fast.dy.data(), plain.dy.data(), n * sizeof(double))) << "dy differs in its bits";
  EXPECT_EQ(0, std::memcmp(fast.dz.data(), plain.dz.data(), n * sizeof(double))) << "dz differs in its bits";
  if (History) {
    EXPECT_EQ(std::vector(fast.entry.begin(), fast.entry.begin() + n),
              std::vector(plain.entry.begin(), plain.entry.begin() + n));
    EXPECT_EQ(std::vector(fast.apart.begin(), fast.apart.begin() + plain.parted),
              std::vector(plain.apart.begin(), plain.apart.begin() + plain.parted));
    // each pair filtered now says whether it was in reach; filtered again, none has left the reach
    std::vector<std::uint8_t> kept(c.count(), 0);
    for (int q = 0; q < plain.size; ++q) {
      const auto u = std::find(c.pair_entry.begin(), c.pair_entry.end(), plain.entry[q]) - c.pair_entry.begin();
      kept[std::size_t(u)] = 1;
    }
    EXPECT_EQ(std::vector(in_reach.begin(), in_reach.begin() + left), std::vector(kept.begin(), kept.begin() + left));
    Queue again(c.count());
    filter_packed<PX, PY, PZ, Gap, History>(packed, c.pair_i.data(), c.pair_j.data(), c.pair_entry.data(), 0, c.count(),
                                            c.length, range, again.to(), again.size, in_reach.data(),
                                            again.apart.data(), again.parted);
    EXPECT_EQ(again.size, plain.size);
    EXPECT_EQ(again.parted, 0) << "out of reach at both filters: nothing to forget";
  }
}

}  // namespace

TEST(EnginePairFilter, FourAtATimeKeepsTheScalarFiltersPairsAndBits) {
  expect_same_as_scalar<false, false, false, false, false>(0);
  expect_same_as_scalar<false, true, false, false, false>(0);
}

TEST(EnginePairFilter, FourAtATimeKeepsTheScalarFiltersPairsAcrossEveryPeriodicAxisAndAGap) {
  expect_same_as_scalar<true, true, true, false, true>(0);
  expect_same_as_scalar<true, true, true, true, true>(0.01);
  expect_same_as_scalar<true, false, true, true, false>(0.01);
}
#endif
