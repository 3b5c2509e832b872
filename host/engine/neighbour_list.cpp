#include <engine/list_filter.hpp>
#include <engine/neighbour_list.hpp>
#include <engine/neighbour_listing.hpp>
#include <engine/thread_team.hpp>
#include <spreadmap/simd.hpp>

#include <algorithm>
#include <type_traits>
#ifdef _OPENMP
#include <omp.h>
#endif

namespace spreadmap::engine {

namespace {
using FourAtATime = std::uint32_t (*)(std::uint32_t, const double *, const double *, const double *, const double *,
                                      const double[3], double, const CellRanges &, std::uint32_t *, std::uint32_t);

// The search four candidates at a time for these periodic axes, where it runs (double, AVX2 and up,
// no sleeping particles); null where list_neighbours searches.
template <class Real> FourAtATime four_at_a_time(const bool per[3], const Real *mobile) {
#if SPREADMAP_SIMD_LEVELS
  if constexpr (std::is_same_v<Real, double>) {
    if (mobile || simd_level() < SimdLevel::avx2) return nullptr;
    static constexpr FourAtATime by_axes[8] = {
        list_neighbours_four<false, false, false>, list_neighbours_four<false, false, true>,
        list_neighbours_four<false, true, false>,  list_neighbours_four<false, true, true>,
        list_neighbours_four<true, false, false>,  list_neighbours_four<true, false, true>,
        list_neighbours_four<true, true, false>,   list_neighbours_four<true, true, true>};
    return by_axes[(per[0] ? 4 : 0) + (per[1] ? 2 : 0) + (per[2] ? 1 : 0)];
  }
#endif
  (void)per, (void)mobile;
  return nullptr;
}
}  // namespace

template <class Real>
void NeighbourList<Real>::build(const ParticleArrays<Real> &p, const CellGrid<Real> &grid,
                                const std::vector<std::uint32_t> &cell_start, const std::vector<std::uint32_t> &cell,
                                const Domain &domain, Real skin, unsigned history, bool with_mirror,
                                const Real *mobile) {
  start.swap(old_start_);
  nbr.swap(old_nbr_);
  hist.swap(old_hist_);
  const std::size_t n = p.size();
  const Real len[3] = {Real(domain.length(0)), Real(domain.length(1)), Real(domain.length(2))};
  const bool per[3] = {domain.periodic[0], domain.periodic[1], domain.periodic[2]};
  const FourAtATime four = four_at_a_time(per, mobile);
  // Particle i's neighbours j >= above among `ranges`, written to out (room for `capacity`, and 4 more).
  auto search = [&](std::uint32_t i, const CellRanges &ranges, std::uint32_t *out, std::uint32_t capacity,
                    std::uint32_t above) -> std::uint32_t {
    if constexpr (std::is_same_v<Real, double>)
      if (four) return four(i, p.x.data(), p.y.data(), p.z.data(), p.r.data(), len, skin, ranges, out, above);
    return list_neighbours(i, p.x.data(), p.y.data(), p.z.data(), p.r.data(), mobile, len, per, skin, ranges, out,
                           capacity, above);
  };

  const int max_threads = max_team_size();
  if (static_cast<int>(thread_nbr_.size()) < max_threads) thread_nbr_.resize(max_threads);
  // The upper neighbours (j > i) of every particle: half the distance tests of a full search.
  first_pair.assign(n + 1, 0);
  int teams = 1;
  thread_first_.resize(max_threads);
  run_team(this_thread_team(), [&](TeamSlot team) {
    if (team.thread == 0) teams = team.threads;
    const auto [lo, hi] = team_share(n, team);
    thread_first_[team.thread] = lo;  // the team's split, whichever it is (TeamSlot::cuts)
    auto &buf = thread_nbr_[team.thread];
    buf.clear();
    CellRanges ranges;
    std::uint32_t current_cell = no_index;
    for (std::size_t i = lo; i < hi; ++i) {
      if (cell[i] != current_cell) {  // particles are sorted by cell: recompute only on a new cell
        current_cell = cell[i];
        ranges = neighbour_runs(grid, current_cell, cell_start.data());
      }
      const auto above = static_cast<std::uint32_t>(i + 1);
      std::size_t candidates = 0;
      for (int q = 0; q < ranges.n; ++q)
        candidates += ranges.end[q] > above ? ranges.end[q] - std::max(ranges.begin[q], above) : 0;
      // Room for every candidate (and a four-lane store past them), then written without a branch (a
      // kept neighbour advances the end).
      const std::size_t first = buf.size();
      buf.resize(first + candidates + 4);
      const std::uint32_t count = search(static_cast<std::uint32_t>(i), ranges, buf.data() + first,
                                         static_cast<std::uint32_t>(candidates), above);
      buf.resize(first + count);
      first_pair[i + 1] = count;
    }
  });
  for (std::size_t i = 0; i < n; ++i) first_pair[i + 1] += first_pair[i];
  const std::size_t pairs = first_pair[n];
  pair_j.resize(pairs);
  pair_i.resize(pairs);
  for (int t = 0; t < teams; ++t)
    std::copy(thread_nbr_[t].begin(), thread_nbr_[t].end(), pair_j.begin() + first_pair[thread_first_[t]]);
  // The full list: particle i's lower neighbours (the pairs (j, i), met in increasing j), then its
  // upper ones; each entry's mirror is known as it is written.
  lower_.assign(n, 0);
  for (std::size_t u = 0; u < pairs; ++u) ++lower_[pair_j[u]];
  start.resize(n + 1);
  upper.resize(n);
  start[0] = 0;
  for (std::size_t i = 0; i < n; ++i) {
    upper[i] = start[i] + lower_[i];
    start[i + 1] = upper[i] + (first_pair[i + 1] - first_pair[i]);
    lower_[i] = start[i];  // from here on: where i's next lower neighbour goes
  }
  nbr.resize(start[n]);
  mirror.resize(start[n]);
  pair_entry.resize(pairs);
  for (std::size_t i = 0; i < n; ++i)
    for (std::uint32_t u = first_pair[i], k = upper[i]; u < first_pair[i + 1]; ++u, ++k) {
      const std::uint32_t j = pair_j[u], m = lower_[j]++;
      pair_i[u] = static_cast<std::uint32_t>(i);
      pair_entry[u] = k;
      nbr[k] = j;
      nbr[m] = static_cast<std::uint32_t>(i);
      mirror[k] = m;
      mirror[m] = k;
    }
  hist.assign(std::size_t(start[n]) * history, Real(0));

  has_mirror_ = with_mirror;
  // Zero between calls of the pair loop, which leaves it so: growing keeps it all zero.
  if (has_mirror_) {
    scratch.resize(std::max(scratch.size(), 6 * (std::size_t(start[n]) + n)));
    packed_.resize(4 * n + 32 / sizeof(Real));
    if (history > 0) in_reach_.assign(pairs, 1);  // any pair may hold carried history
  }
  if (history == 0 || old_nbr_.empty()) return;
  // Carry history: the same (i, j) pair of particles in the previous list, found by old indices.
  const std::size_t old_n = old_start_.empty() ? 0 : old_start_.size() - 1;
  parallel_for(this_thread_team(), n, [&](long long i) {
    carry_history(static_cast<std::uint32_t>(i), p.list_index.data(), static_cast<std::uint32_t>(old_n), start.data(),
                  nbr.data(), hist.data(), old_start_.data(), old_nbr_.data(), old_hist_.data(), history);
  });
}

// After start and nbr were replaced (a checkpoint): mirror[k] for every entry (the lower entries
// (j < i) search i among j's neighbours, listed by index, and set both directions), then the upper
// entries as a flat sequence of pairs.
template <class Real> void NeighbourList<Real>::find_mirrors() {
  const std::size_t n = start.size() - 1, entries = nbr.size();
  mirror.resize(entries);
  upper.resize(n);
  // Zero between calls of the pair loop, which leaves it so: growing keeps it all zero.
  scratch.resize(std::max(scratch.size(), 6 * (entries + n)));
  packed_.resize(4 * n + 32 / sizeof(Real));
  int missing = 0;
  parallel_for(this_thread_team(), n, [&](long long ii) {
    const auto i = static_cast<std::uint32_t>(ii);
    std::uint32_t k = start[i];
    for (; k < start[i + 1] && nbr[k] < i; ++k) {
      const std::uint32_t j = nbr[k];
      const auto first = nbr.begin() + start[j], last = nbr.begin() + start[j + 1];
      const auto found = std::lower_bound(first, last, i);
      if (found == last || *found != i) {
#pragma omp atomic
        ++missing;
        continue;
      }
      const auto m = static_cast<std::uint32_t>(found - nbr.begin());
      mirror[k] = m;
      mirror[m] = k;
    }
    upper[i] = k;
  });
  has_mirror_ = missing == 0;  // a list that is not symmetric is evaluated entry by entry
  if (!has_mirror_) return;
  first_pair.resize(n + 1);
  first_pair[0] = 0;
  for (std::size_t i = 0; i < n; ++i) first_pair[i + 1] = first_pair[i] + (start[i + 1] - upper[i]);
  pair_i.resize(first_pair[n]);
  pair_j.resize(first_pair[n]);
  pair_entry.resize(first_pair[n]);
  in_reach_.assign(first_pair[n], 1);  // any pair may hold restored history
  parallel_for(this_thread_team(), n, [&](long long ii) {
    const auto i = static_cast<std::uint32_t>(ii);
    for (std::uint32_t k = upper[i], u = first_pair[i]; k < start[i + 1]; ++k, ++u) {
      pair_i[u] = i;
      pair_j[u] = nbr[k];
      pair_entry[u] = k;
    }
  });
}

template <class Real> bool NeighbourList<Real>::pair_owners(int threads, std::vector<std::size_t> &cuts) const {
  const std::size_t n = start.empty() ? 0 : start.size() - 1;
  if (!has_mirror_ || nbr.empty() || threads < 2) return false;
  cuts.resize(std::size_t(threads) + 1);
  for (int t = 0; t < threads; ++t) {
    std::uint32_t lo, hi;
    detail::entry_balanced_range(start.data(), static_cast<std::uint32_t>(n), t, threads, &balance_, lo, hi);
    cuts[t] = lo;
    cuts[t + 1] = hi;
  }
  return true;
}

template class NeighbourList<double>;
template class NeighbourList<float>;

}  // namespace spreadmap::engine
