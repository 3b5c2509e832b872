// The host's thread team (engine/thread_team.hpp) and the pair loop's balance of work between its
// threads (detail::retune in engine/pair_loops.hpp): every thread of a run gets its place once,
// work is shared exactly, a barrier separates phases, a run inside a run takes its caller alone, the
// team grows and shrinks with the OpenMP setting, loops follow the cuts the host sets for a step, the
// cuts move to where the threads finish together, and the records of the particles that wait for
// the barrier are summed once whichever thread sums them.
#include <engine/thread_team.hpp>
#include <spreadmap/contact.hpp>
#include <engine/pair_loops.hpp>

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <gtest/gtest.h>
#include <omp.h>
#include <vector>

namespace sm = spreadmap;
using sm::engine::this_thread_team;

namespace {

struct ThreadsScope {
  int saved = omp_get_max_threads();
  explicit ThreadsScope(int threads) { omp_set_num_threads(threads); }
  ~ThreadsScope() { omp_set_num_threads(saved); }
};

// Sum of 0 .. n-1 over the team, one partial sum per thread.
std::uint64_t team_sum(std::uint64_t n) {
  std::vector<std::uint64_t> partial(64, 0);
  sm::run_team(this_thread_team(), [&](sm::TeamSlot slot) {
    const sm::TeamRange r = sm::team_share(n, slot);
    for (std::uint64_t i = r.lo; i < r.hi; ++i) partial[slot.thread] += i;
  });
  std::uint64_t sum = 0;
  for (auto s : partial) sum += s;
  return sum;
}

}  // namespace

TEST(ThreadTeam, EveryThreadOfARunGetsItsPlaceOnce) {
  for (int threads : {1, 2, 3, 4}) {
    const ThreadsScope scope(threads);
    std::vector<std::atomic<int>> seen(8);
    std::atomic<int> wrong_size{0};
    sm::run_team(this_thread_team(), [&](sm::TeamSlot slot) {
      seen[slot.thread].fetch_add(1);
      if (slot.threads != threads) wrong_size.fetch_add(1);
    });
    for (int t = 0; t < 8; ++t) EXPECT_EQ(seen[t].load(), t < threads ? 1 : 0) << threads << " threads, thread " << t;
    EXPECT_EQ(wrong_size.load(), 0);
  }
}

TEST(ThreadTeam, SharesWorkExactlyAsTheTeamGrowsAndShrinks) {
  const std::uint64_t n = 100'003;
  for (int threads : {3, 2, 1, 4, 2}) {
    const ThreadsScope scope(threads);
    EXPECT_EQ(team_sum(n), n * (n - 1) / 2) << threads << " threads";
  }
  const ThreadsScope scope(2);
  std::vector<int> hits(1000, 0);
  sm::parallel_for(this_thread_team(), 1000, [&](long long i) { ++hits[i]; });
  for (int h : hits) EXPECT_EQ(h, 1);
}

TEST(ThreadTeam, ABarrierSeparatesPhases) {
  // Each round every thread writes the round number, passes the barrier, and reads all the others':
  // a thread past the barrier before another wrote would read the previous round.
  const ThreadsScope scope(3);
  constexpr int rounds = 2000;
  std::vector<std::atomic<int>> round_of(3);
  std::atomic<int> stale{0};
  const sm::Team *team = this_thread_team();  // the caller's: the one every thread of the run waits on
  sm::run_team(team, [&](sm::TeamSlot slot) {
    for (int round = 1; round <= rounds; ++round) {
      round_of[slot.thread].store(round, std::memory_order_relaxed);
      sm::team_barrier(team);
      for (int t = 0; t < slot.threads; ++t)
        if (round_of[t].load(std::memory_order_relaxed) < round) stale.fetch_add(1);
      sm::team_barrier(team);  // nobody starts the next round while another still reads
    }
  });
  EXPECT_EQ(stale.load(), 0);
}

TEST(ThreadTeam, ARunInsideARunTakesItsCallerAlone) {
  const ThreadsScope scope(2);
  std::atomic<int> inner_runs{0}, inner_not_alone{0};
  const sm::Team *team = this_thread_team();
  sm::run_team(team, [&](sm::TeamSlot) {
    sm::run_team(team, [&](sm::TeamSlot inner) {
      sm::team_barrier(team);  // alone: returns at once
      inner_runs.fetch_add(1);
      if (inner.threads != 1 || inner.thread != 0) inner_not_alone.fetch_add(1);
    });
  });
  EXPECT_EQ(inner_runs.load(), 2);
  EXPECT_EQ(inner_not_alone.load(), 0);
}

TEST(PairBalance, CutsMoveHalfWayToEqualTimes) {
  // Two threads with equal shares; thread 0 took 3 s, thread 1 took 1 s: speeds 1/6 and 1/2 of
  // the work per second, equal times at a cut of 1/4; half way from 1/2 is 3/8.
  sm::engine::PairBalance b{};
  b.seconds[0] = 3;
  b.seconds[1] = 1;
  sm::engine::detail::retune(b, 2);
  EXPECT_EQ(b.threads, 2);
  EXPECT_DOUBLE_EQ(b.cut[0], 0);
  EXPECT_DOUBLE_EQ(b.cut[1], 0.375);
  EXPECT_DOUBLE_EQ(b.cut[2], 1);
  // Work that costs 3 units per entry in the first half of the list and 1 in the second: the
  // threads finish together when the cut is at 1/4, whatever thread count tunes it.
  for (int threads : {2, 3}) {
    b = sm::engine::PairBalance{};
    auto cost = [](double from, double to) {  // time of the entries [from, to)
      auto work = [](double x) { return x < 0.5 ? 3 * x : 1.5 + (x - 0.5); };
      return work(to) - work(from);
    };
    for (int sweep = 0; sweep < 60; ++sweep) {
      for (int t = 0; t < threads; ++t) {
        const double lo = b.threads == threads ? b.cut[t] : double(t) / threads;
        const double hi = b.threads == threads ? b.cut[t + 1] : double(t + 1) / threads;
        b.seconds[t] = cost(lo, hi);
      }
      sm::engine::detail::retune(b, threads);
    }
    const double each = cost(0, 1) / threads;
    for (int t = 0; t < threads; ++t)
      EXPECT_NEAR(cost(b.cut[t], b.cut[t + 1]), each, 1e-6 * each) << threads << " threads";
  }
}

TEST(ThreadTeam, LoopsFollowTheCutsSetForTheirItemCount) {
  const ThreadsScope scope(3);
  sm::engine::ThreadTeam &team = sm::engine::this_thread_team_object();
  const std::size_t cuts[4] = {0, 70, 90, 100};
  auto shares = [&](std::size_t n) {
    std::vector<sm::TeamRange> got(3);
    sm::run_team(this_thread_team(), [&](sm::TeamSlot slot) { got[slot.thread] = sm::team_share(n, slot); });
    return got;
  };
  team.set_cuts(cuts, 100, 3);
  const auto cut = shares(100), other = shares(99);
  team.set_cuts(cuts, 100, 2);  // set for another team size: not followed
  const auto wrong_size = shares(100);
  team.set_cuts(nullptr, 0, 0);
  const auto cleared = shares(100);
  for (int t = 0; t < 3; ++t) {
    EXPECT_EQ(cut[t].lo, cuts[t]) << t;
    EXPECT_EQ(cut[t].hi, cuts[t + 1]) << t;
    EXPECT_EQ(other[t].lo, 99u * t / 3) << "99 items: equal shares";
    EXPECT_EQ(wrong_size[t].lo, 100u * t / 3);
    EXPECT_EQ(cleared[t].lo, 100u * t / 3);
    EXPECT_EQ(cleared[t].hi, 100u * (t + 1) / 3);
  }
}

TEST(PairLoop, EveryWaitingParticleGetsItsRecordsOnceWhicheverThreadSumsThem) {
  // 12 particles with the neighbours below (full list, increasing); each entry's record holds
  // (entry + 1) in all 6 values. The particles are split in equal ranges, one per thread; a particle
  // waits when its lowest neighbour lies below its range's start, and only it gets its records.
  const std::vector<std::vector<std::uint32_t>> neighbours = {{1},    {0, 2}, {1, 3}, {2, 4},  {3, 5}, {2, 4, 6},
                                                              {5, 7}, {6, 8}, {7, 9}, {8, 10}, {7, 9}, {10}};
  std::vector<std::uint32_t> start{0}, nbr;
  for (const auto &list : neighbours) {
    nbr.insert(nbr.end(), list.begin(), list.end());
    start.push_back(static_cast<std::uint32_t>(nbr.size()));
  }
  for (int threads : {1, 2, 3, 4}) {
    const ThreadsScope scope(threads);
    std::vector<double> scratch(nbr.size() * 6), f(12 * 6, 0.0);
    for (std::size_t k = 0; k < nbr.size(); ++k)
      for (int c = 0; c < 6; ++c) scratch[k * 6 + c] = double(k + 1);
    sm::engine::ListView<double> list{start.data(), nbr.data(), nullptr};
    list.scratch = scratch.data();
    sm::Particles<double> p{};
    p.n = 12;
    p.fx = &f[0];
    p.fy = &f[12];
    p.fz = &f[24];
    p.tx = &f[36];
    p.ty = &f[48];
    p.tz = &f[60];
    std::vector<bool> waits(12, false);
    std::vector<sm::engine::detail::WaitingSpan> spans(threads);
    for (int t = 0; t < threads; ++t) {  // as the pair loop finds them: up to its last waiting particle
      const auto r = sm::team_share(12, sm::TeamSlot{t, threads});
      spans[t] = {std::uint32_t(r.lo), std::uint32_t(r.lo)};
      for (std::size_t i = r.lo; i < r.hi; ++i)
        if (nbr[start[i]] < r.lo) {
          waits[i] = true;
          spans[t].end = std::uint32_t(i + 1);
        }
    }
    sm::run_team(this_thread_team(), [&](sm::TeamSlot slot) { sm::engine::detail::add_waiting_records(p, list, spans.data(), slot); });
    for (std::uint32_t i = 0; i < 12; ++i) {
      double expected = 0;
      for (std::uint32_t k = start[i]; k < start[i + 1]; ++k) expected += waits[i] ? double(k + 1) : 0.0;
      for (int c = 0; c < 6; ++c)
        EXPECT_EQ(f[c * 12 + i], expected) << threads << " threads, particle " << i << ", value " << c;
      for (std::uint32_t k = start[i]; k < start[i + 1]; ++k)
        EXPECT_EQ(scratch[k * 6], waits[i] ? 0.0 : double(k + 1))
            << threads << " threads: a waiting particle's records are cleared, others kept";
    }
    EXPECT_EQ(std::count(waits.begin(), waits.end(), true) > 0, threads > 1) << threads << " threads";
  }
}
