#include <engine/errors.hpp>
#include <engine/step_state.hpp>

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <string>

namespace spreadmap::engine {

template <class Real> void StepState<Real>::resize_walls() {
  const std::size_t n = particles.size();
  for_each_wall_slot([n](WallSlot<Real> &s) { s.resize(n); });
  for (auto &pl : planes) pl.records_for = 0;  // the dense records are written again
}

template <class Real> void StepState<Real>::remove_escaped() {
  leaving = false;
  auto &p = particles;
  const std::size_t n = p.size();
  std::vector<std::uint32_t> kept, scratch_index;
  std::vector<Real> scratch_real;
  for (std::size_t i = 0; i < n; ++i)
    if (!outside(i)) kept.push_back(static_cast<std::uint32_t>(i));
  const std::size_t removed = n - kept.size();
  if (removed == 0) return;
  p.for_each_real([&](std::vector<Real> &c) { gather(c, kept, scratch_real); });
  p.for_each_index([&](std::vector<std::uint32_t> &c) { gather(c, kept, scratch_index); });
  for_each_wall_slot([&](WallSlot<Real> &s) {
    if (s.history) gather(s.hist, kept, scratch_real, s.history);
  });
  resize_walls();
  counters.removed += removed;
  list_valid = false;
}

template <class Real> bool StepState<Real>::outside(std::size_t i) const {
  const auto &p = particles;
  const Real pos[3] = {p.x[i], p.y[i], p.z[i]};
  for (int a = 0; a < 3; ++a)
    if (!domain.periodic[a] && !(pos[a] >= Real(domain.lo[a]) && pos[a] < Real(domain.hi[a]))) return true;
  return false;
}

template <class Real> std::size_t StepState<Real>::outside_count() const {
  std::size_t k = 0;
  for (std::size_t i = 0; i < particles.size(); ++i) k += outside(i);
  return k;
}

template <class Real> void StepState<Real>::report_bad_particle() const {
  const auto &p = particles;
  const std::size_t n = p.size();
  for (std::size_t i = 0; i < n; ++i) {
    const double v = std::sqrt(double(p.vx[i]) * p.vx[i] + double(p.vy[i]) * p.vy[i] + double(p.vz[i]) * p.vz[i]);
    const bool finite = std::isfinite(v) && std::isfinite(double(p.x[i]) + p.y[i] + p.z[i]) &&
                        std::isfinite(double(p.wx[i]) + p.wy[i] + p.wz[i]);
    if (!finite)
      throw RunError(
          fmt::format("the state became NaN or infinite at t = {:.6g} s (step {}): particle id {} at "
                      "({:.4g}, {:.4g}, {:.4g}) m; the integration is unstable: use a smaller dt (or "
                      "dt_safety), or check the contact parameters for a law that returns NaN",
                      time, step, p.id[i], double(p.x[i]), double(p.y[i]), double(p.z[i])));
    if (!(v <= speed_limit))
      throw RunError(
          fmt::format("kinetic energy explodes at t = {:.6g} s (step {}): particle id {} moves at {:.4g} m/s, "
                      "above the limit {:.4g} m/s (10 x the fastest physical speed of the scene); the "
                      "integration is unstable or contacts overlap too deeply: use a smaller dt (or "
                      "dt_safety) or stiffer contacts, or raise settings.speed_limit if this speed is real",
                      time, step, p.id[i], v, speed_limit));
  }
  throw RunError(fmt::format("the state became invalid at t = {:.6g} s (step {}); use a smaller dt", time, step));
}

// After an overlap check counted `bad_pairs` deep pairs (on either backend): finds the first deep
// contact and stops the run.
template <class Real> void StepState<Real>::report_deep_overlap(std::uint32_t bad_pairs) const {
  const auto &p = particles;
  const bool per[3] = {domain.periodic[0], domain.periodic[1], domain.periodic[2]};
  auto advice =
      "the contacts are too soft for the speeds or loads of this scene, or dt is too large: stiffen the "
      "contact law (e.g. a larger v_max or smaller overlap_max for hooke laws), lower the speeds, or use a "
      "smaller dt; settings.overlap_limit sets the limit";
  if (bad_pairs > 0) {
    for (std::size_t i = 0; i < p.size(); ++i)
      for (std::uint32_t k = list.start[i]; k < list.start[i + 1]; ++k) {
        const std::uint32_t j = list.nbr[k];
        const double dx = wrap(double(p.x[i]) - p.x[j], domain.length(0), per[0]),
                     dy = wrap(double(p.y[i]) - p.y[j], domain.length(1), per[1]),
                     dz = wrap(double(p.z[i]) - p.z[j], domain.length(2), per[2]);
        const double overlap = double(p.r[i]) + p.r[j] - std::sqrt(dx * dx + dy * dy + dz * dz);
        const double d = 2.0 * std::min(p.r[i], p.r[j]);
        if (overlap > settings.overlap_limit * d)
          throw RunError(fmt::format(
              "overlap too large at t = {:.6g} s (step {}): particles id {} and id {} overlap by "
              "{:.4g} m = {:.3g} % of the diameter (limit {:.3g} %); {}",
              time, step, p.id[i], p.id[j], overlap, 100 * overlap / d, 100 * settings.overlap_limit, advice));
      }
  }
  auto wall_check = [&](const WallSlot<Real> &s, const std::string &name) {
    for (std::size_t i = 0; i < p.size(); ++i) {
      const double d = 2.0 * p.r[i];
      if (s.overlap[i] > settings.overlap_limit * d)
        throw RunError(
            fmt::format("overlap too large at t = {:.6g} s (step {}): particle id {} overlaps {} by {:.4g} m "
                        "= {:.3g} % of its diameter (limit {:.3g} %); {}",
                        time, step, p.id[i], name, double(s.overlap[i]), 100 * s.overlap[i] / d,
                        100 * settings.overlap_limit, advice));
    }
  };
  for (const auto &pl : planes)
    if (pl.wall.active) wall_check(pl.slot, "plane wall '" + pl.wall.name + "'");
  for (const auto &ge : geometries) wall_check(ge.slot, "geometry '" + ge.geometry.name + "'");
}

template struct StepState<double>;
template struct StepState<float>;

}  // namespace spreadmap::engine
