#include <engine/neighbour_list.hpp>
#include <spreadmap/contact.hpp>
#include <spreadmap/team.hpp>

#include <algorithm>
#ifdef _OPENMP
#include <omp.h>
#endif

namespace spreadmap::engine {

namespace {
// Distinct cell coordinates among c-1, c, c+1 along one axis (wrapped when periodic).
int axis_neighbours(int c, int n, bool periodic, int out[3]) {
  int k = 0;
  for (int d = -1; d <= 1; ++d) {
    int q = c + d;
    if (periodic) q = (q + n) % n;
    else if (q < 0 || q >= n) continue;
    bool seen = false;
    for (int t = 0; t < k; ++t) seen = seen || out[t] == q;
    if (!seen) out[k++] = q;
  }
  return k;
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
  start.assign(n + 1, 0);
  const Real len[3] = {Real(domain.length(0)), Real(domain.length(1)), Real(domain.length(2))};
  const bool per[3] = {domain.periodic[0], domain.periodic[1], domain.periodic[2]};

  const int max_threads = max_team_size();
  if (static_cast<int>(thread_nbr_.size()) < max_threads) thread_nbr_.resize(max_threads);

#pragma omp parallel
  {
    const auto [t, nt] = team_slot();
    const std::size_t lo = n * t / nt, hi = n * (t + 1) / nt;
    auto &buf = thread_nbr_[t];
    buf.clear();
    struct Range { std::uint32_t begin, end; } ranges[27];
    int n_ranges = 0;
    std::size_t candidates = 0;
    std::uint32_t current_cell = no_index;
    for (std::size_t i = lo; i < hi; ++i) {
      if (cell[i] != current_cell) {  // particles are sorted by cell: recompute only on a new cell
        current_cell = cell[i];
        int cc[3];
        grid.coords(current_cell, cc);
        int ax[3], ay[3], az[3];
        const int kx = axis_neighbours(cc[0], grid.n[0], grid.periodic[0], ax);
        const int ky = axis_neighbours(cc[1], grid.n[1], grid.periodic[1], ay);
        const int kz = axis_neighbours(cc[2], grid.n[2], grid.periodic[2], az);
        n_ranges = 0;
        for (int a = 0; a < kz; ++a)
          for (int b = 0; b < ky; ++b)
            for (int c = 0; c < kx; ++c) {
              const int nc[3] = {ax[c], ay[b], az[a]};
              const std::size_t q = grid.index(nc);
              if (cell_start[q] == cell_start[q + 1]) continue;
              ranges[n_ranges++] = {cell_start[q], cell_start[q + 1]};
            }
        // Ascending cell order, so the neighbours of i come out sorted by index.
        std::sort(ranges, ranges + n_ranges, [](const Range &a, const Range &b) { return a.begin < b.begin; });
        candidates = 0;
        for (int q = 0; q < n_ranges; ++q) candidates += ranges[q].end - ranges[q].begin;
      }
      const Real xi = p.x[i], yi = p.y[i], zi = p.z[i], ri = p.r[i];
      // sleeping (mobile given): two sleeping particles are not listed; symmetric, as the list is
      const Real awake_i = mobile ? mobile[i] : Real(1);
      // Room for every candidate, then written without a branch (a kept neighbour advances the end).
      const std::size_t first = buf.size();
      buf.resize(first + candidates);
      std::uint32_t *out = buf.data() + first;
      std::uint32_t count = 0;
      for (int q = 0; q < n_ranges; ++q) {
        for (std::uint32_t j = ranges[q].begin; j < ranges[q].end; ++j) {
          const Real dx = wrap(xi - p.x[j], len[0], per[0]);
          const Real dy = wrap(yi - p.y[j], len[1], per[1]);
          const Real dz = wrap(zi - p.z[j], len[2], per[2]);
          const Real reach = (ri + p.r[j]) + skin;  // symmetric in i and j: the list is, too
          out[count] = j;
          const bool listed = !mobile || awake_i > 0 || mobile[j] > 0;
          count += (dx * dx + dy * dy + dz * dz < reach * reach) & (j != i) & listed ? 1u : 0u;
        }
      }
      buf.resize(first + count);
      start[i + 1] = count;
    }
#pragma omp barrier
#pragma omp single
    {
      for (std::size_t i = 0; i < n; ++i) start[i + 1] += start[i];
      nbr.resize(start[n]);
      hist.assign(std::size_t(start[n]) * history, Real(0));
    }
    std::copy(buf.begin(), buf.end(), nbr.begin() + start[lo]);
  }

  has_mirror_ = false;
  if (with_mirror && history == 0) find_mirrors();
  if (history == 0 || old_nbr_.empty()) return;
  // Carry history: the same (i, j) pair of particles in the previous list, found by old indices.
  const std::size_t old_n = old_start_.empty() ? 0 : old_start_.size() - 1;
#pragma omp parallel for schedule(static)
  for (long long ii = 0; ii < static_cast<long long>(n); ++ii) {
    const std::size_t i = static_cast<std::size_t>(ii);
    const std::uint32_t oi = p.list_index[i];
    if (oi == no_index || oi >= old_n) continue;
    const std::uint32_t ob = old_start_[oi], oe = old_start_[oi + 1];
    for (std::uint32_t k = start[i]; k < start[i + 1]; ++k) {
      const std::uint32_t oj = p.list_index[nbr[k]];
      if (oj == no_index) continue;
      for (std::uint32_t ok = ob; ok < oe; ++ok) {
        if (old_nbr_[ok] != oj) continue;
        std::copy_n(old_hist_.begin() + std::size_t(ok) * history, history, hist.begin() + std::size_t(k) * history);
        break;
      }
    }
  }
}

// mirror[k] for every entry: the lower entries (j < i) search i among j's neighbours (listed by
// index) and set both directions, so each entry is written once.
template <class Real> void NeighbourList<Real>::find_mirrors() {
  const std::size_t n = start.size() - 1, entries = nbr.size();
  mirror.resize(entries);
  slot.resize(entries);
  scratch.resize(6 * (2 * entries + 1 + n));
  std::fill_n(scratch.begin(), 6, Real(0));
  int missing = 0;
#pragma omp parallel for schedule(static) reduction(+ : missing)
  for (long long ii = 0; ii < static_cast<long long>(n); ++ii) {
    const auto i = static_cast<std::uint32_t>(ii);
    for (std::uint32_t k = start[i]; k < start[i + 1] && nbr[k] < i; ++k) {
      const std::uint32_t j = nbr[k];
      const auto first = nbr.begin() + start[j], last = nbr.begin() + start[j + 1];
      const auto found = std::lower_bound(first, last, i);
      if (found == last || *found != i) {
        ++missing;
        continue;
      }
      const auto m = static_cast<std::uint32_t>(found - nbr.begin());
      mirror[k] = m;
      mirror[m] = k;
    }
  }
  has_mirror_ = missing == 0;  // a list that is not symmetric is evaluated entry by entry
}

template class NeighbourList<double>;
template class NeighbourList<float>;

}  // namespace spreadmap::engine
