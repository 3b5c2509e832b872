// Simulation's integration: the kicks and drift, and the overlap and speed checks.
#include <engine/cell_grid.hpp>
#include <engine/errors.hpp>
#include <engine/simulation.hpp>
#include <engine/neighbour_listing.hpp>
#include <engine/stability.hpp>
#include <engine/thread_team.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

namespace spreadmap::engine {

// ---------------------------------------------------------------------------------------------
// integration

// The step's kicks, drift and checks in the form the vectorised loops of kick_drift.hpp take.
template <class Real> KickDrift<Real> Simulation<Real>::integration(Real half_dt, Real dt) {
  auto &p = state_.particles;
  KickDrift<Real> k{p.x.data(),
                    p.y.data(),
                    p.z.data(),
                    p.vx.data(),
                    p.vy.data(),
                    p.vz.data(),
                    p.fx.data(),
                    p.fy.data(),
                    p.fz.data(),
                    p.wx.data(),
                    p.wy.data(),
                    p.wz.data(),
                    p.tx.data(),
                    p.ty.data(),
                    p.tz.data(),
                    p.x0.data(),
                    p.y0.data(),
                    p.z0.data(),
                    p.inv_m.data(),
                    p.inv_i.data(),
                    p.mobile.data(),
                    half_dt,
                    dt,
                    {},
                    {},
                    {},
                    {},
                    {},
                    state_.rotate,
                    asleep_ + fixed_ > 0};
  for (int a = 0; a < 3; ++a) {
    k.g[a] = Real(state_.settings.gravity[a]);
    k.lo[a] = Real(state_.domain.lo[a]);
    k.hi[a] = Real(state_.domain.hi[a]);
    k.len[a] = Real(state_.domain.length(a));
    k.periodic[a] = state_.domain.periodic[a];
  }
  return k;
}

// First half kick (rotation too) and drift in one pass over memory, preceded in the same pass by
// the last step's second half kick and check when it is pending; the force and torque accumulators
// are cleared once used, so the next evaluation needs no pass of its own. Counts the particles
// outside open axes (removed at the next build) and the non-finite ones; returns true when the list
// must be rebuilt: some particle moved by half the skin since the last build (LAMMPS' and
// LIGGGHTS' criterion).
template <class Real> bool Simulation<Real>::kick_and_drift(Real half_dt, Real dt) {
  auto &p = state_.particles;
  const std::size_t n = p.size();
  const KickDrift<Real> k = integration(half_dt, dt);
  const bool second_kick = second_kick_pending_;
  second_kick_pending_ = false;
  const Real limit2 = Real(state_.speed_limit * state_.speed_limit);
  std::uint32_t escaped = 0, nonfinite = 0, bad = 0;
  Real largest = 0;
  run_team(this_thread_team(), [&](TeamSlot team) {
    KickDriftResult<Real> mine;
    std::uint32_t mine_bad = 0;
    const auto [lo, hi] = team_share(n, team);
    if (second_kick) mine_bad = kick_check_drift(k, limit2, lo, hi, mine);
    else kick_drift(k, lo, hi, mine);
#pragma omp critical(spreadmap_kick_drift)
    {
      bad += mine_bad;
      escaped += mine.escaped;
      nonfinite += mine.nonfinite;
      largest = largest > mine.largest ? largest : mine.largest;
    }
  });
  forces_zeroed_ = true;
  // the last step ended in a bad state (time and step are still its own; the velocities shown are
  // half a kick on)
  if (bad > 0) state_.report_bad_particle();
  if (nonfinite > 0) {
    state_.time += state_.dt;  // report the step being taken
    ++state_.step;
    state_.report_bad_particle();
  }
  if (escaped > 0) state_.leaving = true;  // removed at the next build
  const Real half_skin = Real(0.5 * state_.skin);
  return !(largest <= half_skin * half_skin);
}

// Second half kick fused with the per-step sanity check (NaN, speed limit).
template <class Real> void Simulation<Real>::kick_and_check(Real half_dt) {
  auto &p = state_.particles;
  const std::size_t n = p.size();
  const KickDrift<Real> k = integration(half_dt, Real(state_.dt));
  const Real limit2 = Real(state_.speed_limit * state_.speed_limit);
  std::uint32_t bad = 0;
  run_team(this_thread_team(), [&](TeamSlot team) {
    const auto [lo, hi] = team_share(n, team);
    const std::uint32_t mine = kick_check(k, limit2, lo, hi);
#pragma omp atomic
    bad += mine;
  });
  if (bad > 0) state_.report_bad_particle();
}

template <class Real> void Simulation<Real>::check_overlaps() {
  auto &p = state_.particles;
  const std::size_t n = p.size();
  const Real len[3] = {Real(state_.domain.length(0)), Real(state_.domain.length(1)), Real(state_.domain.length(2))};
  const bool per[3] = {state_.domain.periodic[0], state_.domain.periodic[1], state_.domain.periodic[2]};
  const Real limit = Real(state_.settings.overlap_limit);
  std::uint32_t bad = 0;
  const Real *x = p.x.data(), *y = p.y.data(), *z = p.z.data(), *r = p.r.data();
  const ListView<Real> l = state_.list.view();  // its upper entries, when the list keeps them
  run_team(this_thread_team(), [&](TeamSlot team) {
    std::uint32_t mine = 0;
    if (l.pair_i) {  // the flat sequence of upper pairs: one loop, vectorised
      const std::uint64_t pairs = l.first_pair[n];
      const auto [lo, hi] = team_share(pairs, team);
      with_flags(
          [&]<bool PX, bool PY, bool PZ>() {
            with_simd(
                [&] { mine = deep_overlap_pairs<PX, PY, PZ>(l.pair_i, l.pair_j, lo, hi, x, y, z, r, len, limit); });
          },
          per[0], per[1], per[2]);
    } else {
      const auto [lo, hi] = team_share(n, team);
      for (std::size_t i = lo; i < hi; ++i)
        mine += deep_overlaps(static_cast<std::uint32_t>(i), x, y, z, r, l.start, l.nbr, l.upper, len, per, limit);
    }
#pragma omp atomic
    bad += mine;
  });
  state_.report_deep_overlap(bad);
}


template class Simulation<double>;
template class Simulation<float>;

}  // namespace spreadmap::engine
