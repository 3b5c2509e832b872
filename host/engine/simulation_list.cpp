// Simulation's neighbour list: built from the cell grid, and the pairs shared out between threads.
#include <engine/cell_grid.hpp>
#include <engine/cell_sort.hpp>
#include <engine/errors.hpp>
#include <engine/simulation.hpp>
#include <engine/neighbour_listing.hpp>
#include <engine/stability.hpp>
#include <engine/thread_team.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <spdlog/spdlog.h>

namespace spreadmap::engine {

// ---------------------------------------------------------------------------------------------
// neighbour list

template <class Real> void Simulation<Real>::rebuild_list() {
  constexpr double inf = std::numeric_limits<double>::infinity();
  if (state_.leaving) state_.remove_escaped();
  auto &p = state_.particles;
  const std::size_t n = p.size();
  ++state_.counters.list_builds;
  state_.list_valid = true;
  if (n == 0) {
    state_.list.clear();
    state_.list.start.assign(1, 0);
    return;
  }
  double lo[3] = {inf, inf, inf}, hi[3] = {-inf, -inf, -inf}, r_max = 0;
  {
    Real lx = Real(inf), ly = Real(inf), lz = Real(inf), hx = Real(-inf), hy = Real(-inf), hz = Real(-inf), rm = 0;
    run_team(this_thread_team(), [&](TeamSlot team) {
      Real mine[7] = {Real(inf), Real(inf), Real(inf), Real(-inf), Real(-inf), Real(-inf), 0};
      const auto [lo, hi] = team_share(n, team);
      for (std::size_t i = lo; i < hi; ++i) {
        mine[0] = std::min(mine[0], p.x[i]);
        mine[1] = std::min(mine[1], p.y[i]);
        mine[2] = std::min(mine[2], p.z[i]);
        mine[3] = std::max(mine[3], p.x[i]);
        mine[4] = std::max(mine[4], p.y[i]);
        mine[5] = std::max(mine[5], p.z[i]);
        mine[6] = std::max(mine[6], p.r[i]);
      }
#pragma omp critical(spreadmap_bounds)
      {
        lx = std::min(lx, mine[0]);
        ly = std::min(ly, mine[1]);
        lz = std::min(lz, mine[2]);
        hx = std::max(hx, mine[3]);
        hy = std::max(hy, mine[4]);
        hz = std::max(hz, mine[5]);
        rm = std::max(rm, mine[6]);
      }
    });
    lo[0] = lx;
    lo[1] = ly;
    lo[2] = lz;
    hi[0] = hx;
    hi[1] = hy;
    hi[2] = hz;
    r_max = rm;
  }
  // pairs are listed as far apart as the law attracts across a gap, plus the skin
  const double list_skin = state_.skin + law_range(state_.pair_law);
  const double reach = 2 * r_max + list_skin;
  for (int a = 0; a < 3; ++a)
    if (state_.domain.periodic[a] && state_.domain.length(a) < 2 * reach)
      throw SetupError(
          fmt::format("domain: the periodic length along {} ({:.4g} m) must be at least twice the largest "
                      "diameter + skin ({:.4g} m); widen the domain or lower the skin",
                      "xyz"[a], state_.domain.length(a), reach));
  const CellGrid<Real> grid = make_cell_grid<Real>(state_.domain, lo, hi, reach, n);

  cells_.sort(grid, p.x.data(), p.y.data(), p.z.data(), n);
  if (!cells_.unmoved()) {
    // Reference positions are set below; cleared accumulators are all zero: neither needs moving.
    const bool zero_forces = forces_zeroed_;
    p.for_each_real([&](std::vector<Real> &c) {
      if (&c == &p.x0 || &c == &p.y0 || &c == &p.z0) return;
      if (zero_forces && (&c == &p.fx || &c == &p.fy || &c == &p.fz || &c == &p.tx || &c == &p.ty || &c == &p.tz))
        return;
      gather(c, cells_.order, scratch_real_);
    });
    p.for_each_index([&](std::vector<std::uint32_t> &c) { gather(c, cells_.order, scratch_index_); });
    state_.for_each_wall_slot([&](WallSlot<Real> &s) {
      if (s.history) gather(s.hist, cells_.order, scratch_real_, s.history);
    });
  }
  state_.list.build(p, grid, cells_.start, cells_.sorted, state_.domain, Real(list_skin), law_history(state_.pair_law),
                    state_.pairs_once(), state_.settings.sleep && asleep_ > 0 ? p.mobile.data() : nullptr);
  if (state_.settings.sleep) find_border();
  asleep_at_build_ = asleep_;
  for (auto &ge : state_.geometries) find_near_geometry(ge);
  parallel_for(this_thread_team(), n, [&](long long i) {
    p.list_index[i] = static_cast<std::uint32_t>(i);
    p.x0[i] = p.x[i];
    p.y0[i] = p.y[i];
    p.z0[i] = p.z[i];
  });
}

// Every loop of a step over the particles takes the particles whose pairs the thread evaluates: a
// particle's forces, written by the pair loop, are then kicked, cleared and added to by the same
// core, instead of crossing to another core's cache and back each step. The pair loop cuts where
// the threads' times balance (7 % of the particles away from equal shares on the peers' scene); the
// other loops are short and stream memory, where the crossing cost more than the unequal shares
// (the second half kick on 2 threads: 12.8 us a step with equal shares, 8.7 us with these).
template <class Real> void Simulation<Real>::share_like_pairs() {
  const int threads = max_team_size();
  ThreadTeam &team = this_thread_team_object();
  if (state_.list_valid && state_.list.pair_owners(threads, owner_cuts_))
    team.set_cuts(owner_cuts_.data(), state_.particles.size(), threads);
  else team.set_cuts(nullptr, 0, 0);
}


template class Simulation<double>;
template class Simulation<float>;

}  // namespace spreadmap::engine
