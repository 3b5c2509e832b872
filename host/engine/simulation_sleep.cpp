// Simulation's sleeping particles (Settings::sleep): who falls asleep, who wakes, the border.
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
// sleeping (Settings::sleep)

template <class Real> void Simulation<Real>::force_rotation(bool on) {
  host_changes();
  state_.settings.force_rotation = on;
  step_resolved_ = false;
}

// The awake particles with a sleeping neighbour in the list: only their motion can wake one.
template <class Real> void Simulation<Real>::find_border() {
  auto &p = state_.particles;
  border_.clear();
  if (asleep_ == 0) return;
  for (std::uint32_t i = 0; i < p.size(); ++i) {
    if (p.mobile[i] == 0) continue;
    for (std::uint32_t k = state_.list.start[i]; k < state_.list.start[i + 1]; ++k)
      if (p.mobile[state_.list.nbr[k]] == 0) {
        border_.push_back(i);
        break;
      }
  }
}

template <class Real> void Simulation<Real>::wake(std::uint32_t i) {
  auto &p = state_.particles;
  if (p.mobile[i] != 0 || p.inv_m[i] == 0) return;  // awake, or fixed for good
  p.mobile[i] = 1;
  p.calm[i] = 0;
  --asleep_;
  // its pairs with other sleeping particles are not listed: list them, and evaluate its forces anew
  state_.list_valid = false;
  state_.forces_valid = false;
}

// After the second half kick: wake the sleeping particles that a fast neighbour touches; every
// sleep_check_every steps, put to sleep the particles at rest long enough in the sleep region.
template <class Real> void Simulation<Real>::update_sleep() {
  auto &p = state_.particles;
  const Real s2 = Real(state_.settings.sleep_speed * state_.settings.sleep_speed);
  const Real lx = Real(state_.domain.length(0)), ly = Real(state_.domain.length(1)), lz = Real(state_.domain.length(2));
  const bool px = state_.domain.periodic[0], py = state_.domain.periodic[1], pz = state_.domain.periodic[2];
  auto fast = [&](std::uint32_t i) {
    const Real v2 = p.vx[i] * p.vx[i] + p.vy[i] * p.vy[i] + p.vz[i] * p.vz[i];
    const Real w2 = (p.wx[i] * p.wx[i] + p.wy[i] * p.wy[i] + p.wz[i] * p.wz[i]) * p.r[i] * p.r[i];
    return !(v2 < s2) || !(w2 < s2);
  };
  if (state_.list_valid) {
    std::vector<std::uint32_t> woken;
    for (std::uint32_t i : border_) {
      if (!fast(i)) continue;
      for (std::uint32_t k = state_.list.start[i]; k < state_.list.start[i + 1]; ++k) {
        const std::uint32_t j = state_.list.nbr[k];
        if (p.mobile[j] != 0) continue;
        const Real dx = wrap(p.x[i] - p.x[j], lx, px), dy = wrap(p.y[i] - p.y[j], ly, py),
                   dz = wrap(p.z[i] - p.z[j], lz, pz), reach = p.r[i] + p.r[j];
        if (dx * dx + dy * dy + dz * dz < reach * reach) woken.push_back(j);
      }
    }
    for (std::uint32_t j : woken) wake(j);
  }
  if (state_.step % state_.settings.sleep_check_every != 0) return;
  const Real x_max = Real(sleep_x_max_), z_max = Real(sleep_z_max_);
  const std::uint32_t needed = state_.settings.sleep_checks;
  std::uint32_t fell = 0;
  const std::size_t n = p.size();
  run_team(this_thread_team(), [&](TeamSlot team) {
    std::uint32_t mine = 0;
    const auto [lo, hi] = team_share(n, team);
    for (std::size_t ii = lo; ii < hi; ++ii) {
      const auto i = static_cast<std::uint32_t>(ii);
      if (p.mobile[i] == 0) continue;
      const bool rest = (p.x[i] < x_max || p.z[i] < z_max) && !fast(i);
      p.calm[i] = rest ? p.calm[i] + 1 : 0;
      if (p.calm[i] < needed) continue;
      p.mobile[i] = 0;
      p.vx[i] = 0;
      p.vy[i] = 0;
      p.vz[i] = 0;
      p.wx[i] = 0;
      p.wy[i] = 0;
      p.wz[i] = 0;
      ++mine;
    }
#pragma omp atomic
    fell += mine;
  });
  if (fell == 0) return;
  asleep_ += fell;
  // The pairs of two sleeping particles leave the list at its next build; until then they are
  // evaluated as before (and change nothing). Who can wake them is known at once. A build is asked
  // for once 5 % of the particles fell asleep since the last: a region at rest never rebuilds itself.
  find_border();
  if (asleep_ >= asleep_at_build_ + std::max<std::size_t>(1, p.size() / 20)) state_.list_valid = false;
}

template class Simulation<double>;
template class Simulation<float>;

}  // namespace spreadmap::engine
