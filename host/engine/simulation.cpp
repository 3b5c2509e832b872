#include <engine/cell_grid.hpp>
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
#include <engine/team_size_scope.hpp>

namespace spreadmap::engine {

namespace {
void check_law(const ContactLaw &law, const std::string &what) {
  const bool queues = law.abi_minor < 3 || (law.ops && law.ops->pair_queue_f64 && law.ops->pair_queue_f32 &&
                                             law.ops->wall_queue_f64 && law.ops->wall_queue_f32);
  if (!law.ops || !law.ops->natural_frequency || !law.ops->damping_ratio || !law.ops->makes_torque ||
      !law.ops->pairs_f64 || !law.ops->pairs_f32 || !law.ops->walls_f64 || !law.ops->walls_f32 || !queues)
    throw SetupError(
        fmt::format("{}: the contact law has no complete ops table (a null function pointer); "
                    "bind a contact plugin built with this SDK",
                    what));
}
}  // namespace

template <class Real>
Simulation<Real>::Simulation(const Domain &domain, ContactLaw pair_law, Settings settings)
    : state_(domain, pair_law, std::move(settings)) {
  check_law(pair_law, "particle-particle contact");
  for (int a = 0; a < 3; ++a)
    if (!(domain.hi[a] > domain.lo[a]) || !std::isfinite(domain.lo[a]) || !std::isfinite(domain.hi[a]))
      throw SetupError(fmt::format("domain: axis {} spans [{}, {}] m; hi must be finite and greater than lo", "xyz"[a],
                                   domain.lo[a], domain.hi[a]));
  const Settings &s = state_.settings;
  if (!(s.dt >= 0) || !(s.dt_safety > 0) || !(s.dt_safety <= 1))
    throw SetupError(
        fmt::format("settings: dt = {} s and dt_safety = {}: need dt >= 0 (0 = automatic) and 0 < "
                    "dt_safety <= 1",
                    s.dt, s.dt_safety));
  if (!(s.overlap_limit > 0) || s.check_every == 0)
    throw SetupError("settings: overlap_limit must be > 0 and check_every >= 1");
  if (s.sleep) {
    if (law_range(pair_law) > 0)
      throw SetupError(
          "settings: sleep needs a particle-particle law that attracts touching particles only (a sleeping "
          "sphere would be pulled across a gap without moving); turn sleep off or set hamaker_constant: 0");
    if (law_history(pair_law) > 0)
      throw SetupError(
          "settings: sleep needs a particle-particle law without history (the springs a contact keeps, "
          "tangential or rolling, would be lost between two sleeping spheres); turn sleep off, or use a law "
          "without history (no tangential spring, rolling_model: constant)");
    if (!(s.sleep_speed > 0) || s.sleep_checks == 0 || s.sleep_check_every == 0)
      throw SetupError("settings: sleep needs sleep_speed > 0, sleep_checks >= 1 and sleep_check_every >= 1");
  }
  state_.list.start.assign(1, 0);
}

template <class Real> void Simulation<Real>::log(const std::string &message) const {
  if (state_.settings.log) state_.settings.log(message);
  else spdlog::info("{}", message);
}

// ---------------------------------------------------------------------------------------------
// particles and walls

template <class Real> void Simulation<Real>::add_particles(ParticleSet set, double density) {
  auto &p = state_.particles;
  host_changes();
  set.validate("add_particles");
  if (set.mass.empty() && !(density > 0))
    throw SetupError("add_particles: the set has no mass column and no density was given; give density [kg/m^3]");
  set.fill_defaults(density, next_id_);
  const std::size_t old_n = p.size(), n = old_n + set.size();
  if (n >= no_index) throw SetupError("add_particles: more than 4e9 particles");
  const bool any_fixed = std::find(set.fixed.begin(), set.fixed.end(), std::uint8_t(1)) != set.fixed.end();
  if (any_fixed && backend_)
    throw SetupError("add_particles: fixed particles step on the CPU only; add them before choosing a backend");
  p.resize(n);
  for (std::size_t k = 0; k < set.size(); ++k) {
    double pos[3] = {set.x[k], set.y[k], set.z[k]};
    for (int a = 0; a < 3; ++a) {
      const Domain &d = state_.domain;
      if (d.periodic[a]) {
        const double l = d.length(a);
        pos[a] = d.lo[a] + (pos[a] - d.lo[a]) - std::floor((pos[a] - d.lo[a]) / l) * l;
        if (pos[a] >= d.hi[a]) pos[a] = d.lo[a];
      } else if (pos[a] < d.lo[a] || pos[a] >= d.hi[a]) {
        throw SetupError(
            fmt::format("add_particles: particle {} (id {}) has {} = {} m, outside the open domain "
                        "axis [{}, {}) m; move it inside or make the axis periodic",
                        k, set.id[k], "xyz"[a], pos[a], d.lo[a], d.hi[a]));
      }
    }
    const std::size_t i = old_n + k;
    p.x[i] = Real(pos[0]);
    p.y[i] = Real(pos[1]);
    p.z[i] = Real(pos[2]);
    p.vx[i] = Real(set.vx[k]);
    p.vy[i] = Real(set.vy[k]);
    p.vz[i] = Real(set.vz[k]);
    p.wx[i] = Real(set.wx[k]);
    p.wy[i] = Real(set.wy[k]);
    p.wz[i] = Real(set.wz[k]);
    p.r[i] = Real(set.radius[k]);
    p.m[i] = Real(set.mass[k]);
    p.inv_m[i] = Real(1.0 / set.mass[k]);
    p.inv_i[i] = Real(1.0 / (0.4 * set.mass[k] * set.radius[k] * set.radius[k]));
    p.id[i] = set.id[k];
    p.list_index[i] = no_index;
    p.mobile[i] = 1;
    p.calm[i] = 0;
    if (!set.fixed.empty() && set.fixed[k]) {
      p.vx[i] = p.vy[i] = p.vz[i] = p.wx[i] = p.wy[i] = p.wz[i] = 0;
      p.m[i] = Real(set.mass[k] * fixed_mass_scale);
      p.inv_m[i] = p.inv_i[i] = p.mobile[i] = 0;
      ++fixed_;
    }
    next_id_ = std::max(next_id_, set.id[k] + 1);
  }
  state_.resize_walls();
  step_resolved_ = state_.list_valid = state_.forces_valid = false;
}

template <class Real> ParticleSet Simulation<Real>::state() const {
  const auto &p = state_.particles;
  sync_host();
  // the particles in the domain: those that left it are removed at the next list build
  std::vector<std::uint32_t> kept;
  for (std::size_t i = 0; i < p.size(); ++i)
    if (!state_.leaving || !state_.outside(i)) kept.push_back(static_cast<std::uint32_t>(i));
  ParticleSet s;
  const std::size_t n = kept.size();
  auto copy = [&kept, n](const std::vector<Real> &from, std::vector<double> &to) {
    to.resize(n);
    for (std::size_t k = 0; k < n; ++k) to[k] = from[kept[k]];
  };
  copy(p.x, s.x);
  copy(p.y, s.y);
  copy(p.z, s.z);
  copy(p.vx, s.vx);
  copy(p.vy, s.vy);
  copy(p.vz, s.vz);
  copy(p.wx, s.wx);
  copy(p.wy, s.wy);
  copy(p.wz, s.wz);
  copy(p.r, s.radius);
  copy(p.m, s.mass);
  s.id.resize(n);
  for (std::size_t k = 0; k < n; ++k) s.id[k] = p.id[kept[k]];
  if (fixed_ > 0) {
    s.fixed.assign(n, 0);
    for (std::size_t k = 0; k < n; ++k)
      if (p.inv_m[kept[k]] == 0) {
        s.fixed[k] = 1;
        s.mass[k] /= fixed_mass_scale;
      }
  }
  return s;
}

template <class Real> std::size_t Simulation<Real>::size() const {
  if (!state_.leaving) return state_.particles.size();
  sync_host();
  return state_.particles.size() - state_.outside_count();
}

template <class Real> std::uint64_t Simulation<Real>::removed_count() const {
  sync_host();
  return state_.counters.removed + (state_.leaving ? state_.outside_count() : 0);
}

template <class Real> std::size_t Simulation<Real>::add_plane_wall(PlaneWall wall) {
  host_changes();
  check_law(wall.law, "plane wall '" + wall.name + "'");
  const double len =
      std::sqrt(wall.normal[0] * wall.normal[0] + wall.normal[1] * wall.normal[1] + wall.normal[2] * wall.normal[2]);
  if (!(len > 0) || !std::isfinite(len))
    throw SetupError(fmt::format("plane wall '{}': normal ({}, {}, {}) must be a finite non-zero vector", wall.name,
                                 wall.normal[0], wall.normal[1], wall.normal[2]));
  for (auto &c : wall.normal) c /= len;
  if (law_range(wall.law) > 0 && (state_.settings.sleep || backend_))
    throw SetupError(
        fmt::format("plane wall '{}': its law attracts across a gap (hamaker_constant), which runs "
                    "on the CPU without sleep only; turn sleep off and use the CPU backend",
                    wall.name));
  PlaneSlot<Real> s;
  s.wall = std::move(wall);
  s.slot.history = law_history(s.wall.law);
  s.slot.resize(state_.particles.size());
  state_.planes.push_back(std::move(s));
  step_resolved_ = state_.forces_valid = false;
  return state_.planes.size() - 1;
}

template <class Real> std::size_t Simulation<Real>::add_geometry(GeometryWall geometry) {
  host_changes();
  check_law(geometry.law, "geometry '" + geometry.name + "'");
  if (!geometry.ops || !geometry.ops->contacts_f64 || !geometry.ops->contacts_f32 ||
      (geometry.abi_minor >= 3 && (!geometry.ops->contacts_range_f64 || !geometry.ops->contacts_range_f32)))
    throw SetupError(fmt::format("geometry '{}': no contacts function in its ops table", geometry.name));
  GeometrySlot<Real> s;
  s.geometry = std::move(geometry);
  s.slot.history = law_history(s.geometry.law);
  s.slot.resize(state_.particles.size());
  state_.geometries.push_back(std::move(s));
  step_resolved_ = state_.forces_valid = false;
  return state_.geometries.size() - 1;
}

template <class Real> void Simulation<Real>::set_plane_wall_active(std::size_t i, bool active) {
  host_changes();
  auto &pl = state_.planes.at(i);
  if (pl.wall.active == active) return;
  pl.wall.active = active;
  std::fill(pl.slot.hist.begin(), pl.slot.hist.end(), Real(0));
  std::fill(pl.slot.overlap.begin(), pl.slot.overlap.end(), Real(0));
  pl.slot.touched = false;
  state_.forces_valid = false;
}

template <class Real>
void Simulation<Real>::set_plane_wall_velocity(std::size_t i, const std::array<double, 3> &velocity) {
  host_changes();
  state_.planes.at(i).wall.velocity = velocity;
}

// ---------------------------------------------------------------------------------------------
// time step

template <class Real> double Simulation<Real>::critical_dt() const {
  constexpr double inf = std::numeric_limits<double>::infinity();
  const auto &p = state_.particles;
  const std::size_t n = p.size();
  if (n == 0) return inf;
  std::size_t light = 0, heavy = 0;
  for (std::size_t i = 1; i < n; ++i) {
    if (p.m[i] < p.m[light]) light = i;
    if (p.m[i] > p.m[heavy]) heavy = i;
  }
  const double m[2] = {double(p.m[light]), double(p.m[heavy])}, r[2] = {double(p.r[light]), double(p.r[heavy])};
  double best = inf;
  if (n >= 2) {
    for (int a = 0; a < 2; ++a)
      for (int b = a; b < 2; ++b)
        best = std::min(best,
                        packing_critical_dt(state_.pair_law, m[a] * m[b] / (m[a] + m[b]), r[a] * r[b] / (r[a] + r[b])));
  }
  auto wall = [&](const ContactLaw &law) {
    for (int a = 0; a < 2; ++a) best = std::min(best, packing_critical_dt(law, m[a], r[a]));
  };
  for (const auto &pl : state_.planes) wall(pl.wall.law);
  for (const auto &g : state_.geometries) wall(g.geometry.law);
  return best;
}

template <class Real> double Simulation<Real>::dt() {
  if (!step_resolved_) resolve_step();
  return state_.dt;
}

template <class Real> void Simulation<Real>::resolve_step() {
  const auto &p = state_.particles;
  const Settings &s = state_.settings;
  const Domain &d = state_.domain;
  const double crit = critical_dt();
  if (!(crit > 0))
    throw SetupError(
        "no time step is stable: a contact law reports that its attraction outweighs its normal stiffness for "
        "these particles (e.g. SJKR cohesion with k_c >= K_n / (2 pi r_eff)), so contacts collapse; lower the "
        "cohesion (cohesion_energy_density) or stiffen the law (a larger v_max / overlap_max)");
  if (s.dt > 0) {
    if (s.dt > crit && !s.allow_unstable_dt)
      throw SetupError(
          fmt::format("time step dt = {:.6g} s is above the critical step dt_crit = {:.6g} s of this "
                      "scene's contacts (velocity-Verlet with damping, in the densest packing); use "
                      "dt <= {:.6g} s, or dt: 0 for the automatic {:.3g} x dt_crit = {:.6g} s",
                      s.dt, crit, crit, s.dt_safety, s.dt_safety * crit));
    state_.dt = s.dt;
  } else {
    if (!std::isfinite(crit))
      throw SetupError(
          "cannot choose the time step automatically: no particles, or no contact law with a stiffness; "
          "add particles first or set dt");
    state_.dt = s.dt_safety * crit;
  }
  double d_max = 0, v_max = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    d_max = std::max(d_max, 2.0 * double(p.r[i]));
    v_max =
        std::max(v_max, std::sqrt(double(p.vx[i]) * p.vx[i] + double(p.vy[i]) * p.vy[i] + double(p.vz[i]) * p.vz[i]));
  }
  state_.skin = s.skin > 0 ? s.skin : s.skin_fraction * d_max;
  // The fastest physical speed of the scene: free fall across the domain, moving surfaces, the
  // initial speeds. Ten times that is an explosion, not physics.
  const double g = std::sqrt(s.gravity[0] * s.gravity[0] + s.gravity[1] * s.gravity[1] + s.gravity[2] * s.gravity[2]);
  const double diag = std::sqrt(d.length(0) * d.length(0) + d.length(1) * d.length(1) + d.length(2) * d.length(2));
  double v_phys = std::max(std::sqrt(2 * g * diag), v_max);
  for (const auto &pl : state_.planes)
    v_phys = std::max(v_phys,
                      std::sqrt(pl.wall.velocity[0] * pl.wall.velocity[0] + pl.wall.velocity[1] * pl.wall.velocity[1] +
                                pl.wall.velocity[2] * pl.wall.velocity[2]));
  for (const auto &ge : state_.geometries)
    if (ge.geometry.ops->max_surface_speed)
      v_phys = std::max(v_phys, ge.geometry.ops->max_surface_speed(ge.geometry.self));
  state_.speed_limit = s.speed_limit > 0 ? s.speed_limit : 10.0 * std::max(v_phys, 1e-3);

  bool torque = s.force_rotation || state_.pair_law.ops->makes_torque(state_.pair_law.self) != 0;
  for (const auto &pl : state_.planes) torque = torque || pl.wall.law.ops->makes_torque(pl.wall.law.self) != 0;
  for (const auto &ge : state_.geometries)
    torque = torque || ge.geometry.law.ops->makes_torque(ge.geometry.law.self) != 0;
  if (state_.rotate != torque || !step_resolved_) {
    if (!torque)
      log("engine: no contact law makes torque: rotation is not integrated (angular velocities stay as given)");
  }
  state_.rotate = torque;
  log(fmt::format(
      "engine: dt = {:.4g} s = {:.3g} x dt_crit (dt_crit = {:.4g} s); skin = {:.3g} m; speed limit {:.3g} m/s",
      state_.dt, state_.dt / crit, crit, state_.skin, state_.speed_limit));
  step_resolved_ = true;
  state_.list_valid = false;  // the skin may have changed
}

template <class Real> void Simulation<Real>::prepare() {
  if (!step_resolved_) resolve_step();
  if (!state_.list_valid) rebuild_list();
  if (!state_.forces_valid) compute_forces();
}

template <class Real> bool Simulation<Real>::attracts_across_gap() const {
  bool across = law_range(state_.pair_law) > 0;
  for (const auto &pl : state_.planes) across = across || law_range(pl.wall.law) > 0;
  return across;
}

template <class Real> void Simulation<Real>::set_backend(std::unique_ptr<StepBackend<Real>> backend) {
  if (backend && fixed_ > 0) throw SetupError("this scene has fixed particles: it steps on the CPU only");
  if (backend && attracts_across_gap())
    throw SetupError(
        "this scene's contact law attracts across a gap (hamaker_constant): it steps on the CPU only; use "
        "backend: cpu or set hamaker_constant: 0");
  sync_host();
  backend_ = std::move(backend);
  device_ahead_ = false;
  host_changed_ = true;
}

template <class Real> void Simulation<Real>::sync_host() const {
  if (second_kick_pending_) {
    auto &self = const_cast<Simulation &>(*this);  // completes the step whose state is read
    self.second_kick_pending_ = false;
    self.kick_and_check(Real(0.5 * state_.dt));
  }
  if (!backend_ || !device_ahead_) return;
  device_ahead_ = false;  // first: download() reads the host copy's sizes through the accessors
  backend_->download(const_cast<StepState<Real> &>(state_));
}

template <class Real> void Simulation<Real>::host_changes() {
  sync_host();
  host_changed_ = true;
}

template <class Real> void Simulation<Real>::step() {
  using clock = std::chrono::steady_clock;
  const auto t0 = clock::now();
  auto &prof = state_.counters.profile;
  if (backend_) {
    if (!step_resolved_) resolve_step();
    if (host_changed_) {
      backend_->upload(state_);
      host_changed_ = false;
    }
    device_ahead_ = true;
    backend_->step(state_);
    prof.other += std::chrono::duration<double>(clock::now() - t0).count();
    return;
  }
  const double timed_before = prof.total();
  const auto &p = state_.particles;
  const bool serial = p.size() < state_.settings.parallel_min_particles;
  const bool tuned = state_.settings.tune_threads && !serial;
  if (tuned && tuner_.most() != max_team_size()) tuner_.reset(max_team_size());
  const TeamSizeScope team(serial ? 1 : tuned ? tuner_.threads() : 0);
  prepare();
  struct EqualSharesAfter {
    ~EqualSharesAfter() { this_thread_team_object().set_cuts(nullptr, 0, 0); }
  } equal_shares_after;  // outside a step, nothing is split by this simulation's particles
  share_like_pairs();
  auto since = [](clock::time_point t) { return std::chrono::duration<double>(clock::now() - t).count(); };
  auto t = clock::now();
  const Real dt = Real(state_.dt), half = Real(0.5 * state_.dt);
  const bool rebuild = kick_and_drift(half, dt);
  for (auto &pl : state_.planes)
    for (int a = 0; a < 3; ++a) pl.wall.point[a] += state_.dt * pl.wall.velocity[a];
  state_.time += state_.dt;
  ++state_.step;
  prof.integrate += since(t);
  if (rebuild || !state_.list_valid) {
    t = clock::now();
    rebuild_list();
    share_like_pairs();
    prof.neighbours += since(t);
  }
  compute_forces(&prof);
  // The second half kick waits for the next step's first, which runs it in the same pass
  // (kick_and_drift), unless the state is read or changed before (sync_host). Sleeping reads the
  // velocities now; immobile (fixed) particles need the kick that reads mobility.
  t = clock::now();
  if (state_.settings.sleep || fixed_ > 0) kick_and_check(half);
  else second_kick_pending_ = true;
  prof.integrate += since(t);
  if (state_.step % state_.settings.check_every == 0) check_overlaps();
  ++state_.counters.steps;
  state_.counters.particle_steps += double(p.size());
  state_.counters.integrated_particle_steps += double(p.size() - asleep_ - fixed_);
  if (state_.settings.sleep) update_sleep();
  const double wall = since(t0);
  prof.other += wall - (prof.total() - timed_before);  // set-up, checks, sleeping
  state_.counters.wall_seconds += wall;
  if (tuned) tuner_.stepped(wall);
}

template <class Real> void Simulation<Real>::run_steps(std::uint64_t n) {
  for (std::uint64_t k = 0; k < n; ++k) step();
}

template <class Real>
bool Simulation<Real>::run_until(double t_end, const StepCallback &callback, std::uint64_t every) {
  if (every == 0) every = 1;
  while (state_.time + 0.5 * dt() < t_end) {
    step();
    if (callback && state_.step % every == 0 && !callback(*this)) return false;
  }
  return true;
}


template class Simulation<double>;
template class Simulation<float>;

}  // namespace spreadmap::engine
