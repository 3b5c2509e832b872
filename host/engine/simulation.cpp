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
#ifdef _OPENMP
#include <omp.h>
#endif

namespace spreadmap::engine {

namespace {
constexpr double inf = std::numeric_limits<double>::infinity();

// Runs the enclosing scope on at most `most` threads (0: as many as the caller's setting), restoring
// the caller's thread count (the OpenMP setting the thread team follows) on exit, exceptions
// included. Affects only the calling thread's runs.
class TeamSizeScope {
 public:
  explicit TeamSizeScope(int most) {
#ifdef _OPENMP
    if (most > 0 && omp_get_max_threads() > most) {
      saved_ = omp_get_max_threads();
      omp_set_num_threads(most);
    }
#else
    (void)most;
#endif
  }
  ~TeamSizeScope() {
#ifdef _OPENMP
    if (saved_ > 0) omp_set_num_threads(saved_);
#endif
  }
  TeamSizeScope(const TeamSizeScope &) = delete;
  TeamSizeScope &operator=(const TeamSizeScope &) = delete;

 private:
  int saved_ = 0;
};

void check_law(const ContactLaw &law, const std::string &what) {
  if (!law.ops || !law.ops->natural_frequency || !law.ops->damping_ratio || !law.ops->makes_torque ||
      !law.ops->pairs_f64 || !law.ops->pairs_f32 || !law.ops->walls_f64 || !law.ops->walls_f32)
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
    if (pair_law.ops->history > 0)
      throw SetupError(
          "settings: sleep needs a particle-particle law without history (the tangential springs of two "
          "sleeping spheres would be lost); turn sleep off or use a law without history");
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
  s.slot.history = s.wall.law.ops->history;
  s.slot.resize(state_.particles.size());
  state_.planes.push_back(std::move(s));
  step_resolved_ = state_.forces_valid = false;
  return state_.planes.size() - 1;
}

template <class Real> std::size_t Simulation<Real>::add_geometry(GeometryWall geometry) {
  host_changes();
  check_law(geometry.law, "geometry '" + geometry.name + "'");
  if (!geometry.ops || !geometry.ops->contacts_f64 || !geometry.ops->contacts_f32)
    throw SetupError(fmt::format("geometry '{}': no contacts function in its ops table", geometry.name));
  GeometrySlot<Real> s;
  s.geometry = std::move(geometry);
  s.slot.history = s.geometry.law.ops->history;
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

// ---------------------------------------------------------------------------------------------
// neighbour list

template <class Real> void Simulation<Real>::rebuild_list() {
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
  const std::size_t n_cells = grid.count();

  // Stable counting sort by cell.
  cell_.resize(n);
  parallel_for(this_thread_team(), n, [&](long long i) { cell_[i] = grid.cell_of(p.x[i], p.y[i], p.z[i]); });
  cell_start_.assign(n_cells + 1, 0);
  for (std::size_t i = 0; i < n; ++i) ++cell_start_[cell_[i] + 1];
  for (std::size_t c = 0; c < n_cells; ++c) cell_start_[c + 1] += cell_start_[c];
  perm_.resize(n);
  cell_sorted_.resize(n);
  {
    scratch_index_.assign(cell_start_.begin(), cell_start_.end() - 1);  // next free slot per cell
    for (std::size_t i = 0; i < n; ++i) {
      const std::uint32_t slot = scratch_index_[cell_[i]]++;
      perm_[slot] = static_cast<std::uint32_t>(i);
      cell_sorted_[slot] = cell_[i];
    }
  }
  bool identity = true;
  for (std::size_t i = 0; i < n && identity; ++i) identity = perm_[i] == i;
  if (!identity) {
    // Reference positions are set below; cleared accumulators are all zero: neither needs moving.
    const bool zero_forces = forces_zeroed_;
    p.for_each_real([&](std::vector<Real> &c) {
      if (&c == &p.x0 || &c == &p.y0 || &c == &p.z0) return;
      if (zero_forces && (&c == &p.fx || &c == &p.fy || &c == &p.fz || &c == &p.tx || &c == &p.ty || &c == &p.tz))
        return;
      gather(c, perm_, scratch_real_);
    });
    p.for_each_index([&](std::vector<std::uint32_t> &c) { gather(c, perm_, scratch_index_); });
    state_.for_each_wall_slot([&](WallSlot<Real> &s) {
      if (s.history) gather(s.hist, perm_, scratch_real_, s.history);
    });
  }
  state_.list.build(p, grid, cell_start_, cell_sorted_, state_.domain, Real(list_skin), state_.pair_law.ops->history,
                    state_.settings.pairs_once, state_.settings.sleep && asleep_ > 0 ? p.mobile.data() : nullptr);
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

// ---------------------------------------------------------------------------------------------
// forces

template <class Real> Particles<Real> Simulation<Real>::view() {
  auto &p = state_.particles;
  Particles<Real> v;
  v.n = static_cast<std::uint32_t>(p.size());
  v.x = p.x.data();
  v.y = p.y.data();
  v.z = p.z.data();
  v.vx = p.vx.data();
  v.vy = p.vy.data();
  v.vz = p.vz.data();
  v.wx = p.wx.data();
  v.wy = p.wy.data();
  v.wz = p.wz.data();
  v.r = p.r.data();
  v.m = p.m.data();
  v.fx = p.fx.data();
  v.fy = p.fy.data();
  v.fz = p.fz.data();
  v.tx = p.tx.data();
  v.ty = p.ty.data();
  v.tz = p.tz.data();
  for (int a = 0; a < 3; ++a) {
    v.box_lo[a] = Real(state_.domain.lo[a]);
    v.box_hi[a] = Real(state_.domain.hi[a]);
    v.periodic[a] = state_.domain.periodic[a] ? 1 : 0;
  }
  v.dt = Real(state_.dt);
  v.t = Real(state_.time);
  v.team = this_thread_team();
  return v;
}

// The plane's overlap with every particle (kept for the overlap check) and the particles its law
// must see: those touching it (or within its law's range across a gap) and those still holding
// history from an earlier contact (the law clears it), in increasing order. A particle beyond reach
// gets the overlap -range (0 for a law of touching contacts), which the law reads as apart.
template <class Real> void Simulation<Real>::plane_contacts(PlaneSlot<Real> &plane) {
  auto &p = state_.particles;
  const Real point[3] = {Real(plane.wall.point[0]), Real(plane.wall.point[1]), Real(plane.wall.point[2])};
  const Real normal[3] = {Real(plane.wall.normal[0]), Real(plane.wall.normal[1]), Real(plane.wall.normal[2])};
  WallSlot<Real> &s = plane.slot;
  const unsigned history = s.history;
  const std::size_t n = p.size();
  const bool moving = plane.wall.velocity[0] != 0 || plane.wall.velocity[1] != 0 || plane.wall.velocity[2] != 0;
  const Real floor = Real(0) - Real(law_range(plane.wall.law));
  const int max_threads = max_team_size();
  if (thread_index_.size() < std::size_t(max_threads)) thread_index_.resize(max_threads);
  int teams = 1;
  run_team(this_thread_team(), [&](TeamSlot team) {
    if (team.thread == 0) teams = team.threads;
    auto &mine = thread_index_[team.thread];
    mine.clear();
    const auto [lo, hi] = team_share(n, team);
    for (std::size_t i = lo; i < hi; ++i) {
      const Real overlap = plane_overlap(point, normal, p.x[i], p.y[i], p.z[i], p.r[i]);
      s.overlap[i] = overlap > floor ? overlap : floor;
      bool held = false;
      for (unsigned h = 0; h < history; ++h) held = held || s.hist[i * history + h] != 0;
      // a sleeping particle on a wall at rest stays as it is: no need to evaluate it
      if ((overlap > floor || held) && (moving || p.mobile[i] != 0)) mine.push_back(static_cast<std::uint32_t>(i));
    }
  });
  plane.near.clear();
  for (int t = 0; t < teams; ++t) plane.near.insert(plane.near.end(), thread_index_[t].begin(), thread_index_[t].end());
}

// A plane's law over every particle at once, its records written in place: while no particle
// sleeps, the subset of plane_contacts would only add copies (the substrate touches a good part of
// a heap). A particle apart from the plane (beyond its law's range) gets overlap 0 (-range), which the
// law reads as no contact (it clears any history). The normal and velocity records are the same for every particle:
// written when they change, so that a step writes only the overlaps. Same bits as the subset.
template <class Real> void Simulation<Real>::dense_plane_forces(PlaneSlot<Real> &plane, const Particles<Real> &view) {
  auto &p = state_.particles;
  const Real point[3] = {Real(plane.wall.point[0]), Real(plane.wall.point[1]), Real(plane.wall.point[2])};
  const Real normal[3] = {Real(plane.wall.normal[0]), Real(plane.wall.normal[1]), Real(plane.wall.normal[2])};
  const Real velocity[3] = {Real(plane.wall.velocity[0]), Real(plane.wall.velocity[1]), Real(plane.wall.velocity[2])};
  WallSlot<Real> &s = plane.slot;
  const std::size_t n = p.size();
  const std::array<Real, 6> records{normal[0], normal[1], normal[2], velocity[0], velocity[1], velocity[2]};
  if (plane.records_for != n || plane.records != records) {
    std::vector<Real> *columns[6] = {&s.nx, &s.ny, &s.nz, &s.vx, &s.vy, &s.vz};
    for (int c = 0; c < 6; ++c) std::fill(columns[c]->begin(), columns[c]->end(), records[c]);
    plane.records_for = n;
    plane.records = records;
  }
  const unsigned history = s.history;
  const double range = law_range(plane.wall.law);
  const Real floor = Real(0) - Real(range);
  std::uint32_t touching = 0;
  run_team(this_thread_team(), [&](TeamSlot team) {
    const auto [lo, hi] = team_share(n, team);
    std::uint32_t mine = 0;
    with_simd([&] {
      mine = plane_overlaps(point, normal, p.x.data(), p.y.data(), p.z.data(), p.r.data(), s.overlap.data(), lo, hi,
                            floor);
    });
    // apart: the law still runs for a particle that holds history from this plane, to clear it
    for (std::size_t i = lo; i < hi && history > 0; ++i) {
      bool held = false;
      for (unsigned h = 0; h < history; ++h) held = held || s.hist[i * history + h] != 0;
      mine += s.overlap[i] > floor || !held ? 0u : 1u;
    }
#pragma omp atomic
    touching += mine;
  });
  s.touched = touching > 0;
  if (!s.touched) return;
  WallContacts<Real> w = s.view(n);
  w.gap = Real(range);
  if constexpr (std::is_same_v<Real, double>) plane.wall.law.ops->walls_f64(plane.wall.law.self, &view, &w);
  else plane.wall.law.ops->walls_f32(plane.wall.law.self, &view, &w);
}

// One wall's law over a subset of particles gathered beforehand, then the forces added back. A small
// subset runs on this thread: a team would cost more than the work.
template <class Real>
void Simulation<Real>::subset_forces(const ContactLaw &law, const Particles<Real> &sv, WallContacts<Real> &sw) {
  const TeamSizeScope serial(sw.n < subset_parallel_from ? 1 : 0);
  if constexpr (std::is_same_v<Real, double>) law.ops->walls_f64(law.self, &sv, &sw);
  else law.ops->walls_f32(law.self, &sv, &sw);
}

template <class Real> void Simulation<Real>::compute_forces(StepProfile *prof) {
  using clock = std::chrono::steady_clock;
  auto t = clock::now();
  auto lap = [&](double StepProfile::*part) {
    if (!prof) return;
    const auto now = clock::now();
    prof->*part += std::chrono::duration<double>(now - t).count();
    t = now;
  };
  auto &p = state_.particles;
  const std::size_t n = p.size();
  if (!forces_zeroed_) {
    parallel_for(this_thread_team(), n, [&](long long i) {
      p.fx[i] = 0;
      p.fy[i] = 0;
      p.fz[i] = 0;
      p.tx[i] = 0;
      p.ty[i] = 0;
      p.tz[i] = 0;
    });
  }
  forces_zeroed_ = false;
  state_.forces_valid = true;
  if (n == 0) return;
  const Particles<Real> v = view();
  const PairList<Real> l = state_.list.view();
  if constexpr (std::is_same_v<Real, double>) state_.pair_law.ops->pairs_f64(state_.pair_law.self, &v, &l);
  else state_.pair_law.ops->pairs_f32(state_.pair_law.self, &v, &l);
  lap(&StepProfile::pairs);  // with the zeroing of the forces above

  for (auto &pl : state_.planes) {
    if (!pl.wall.active) continue;
    if (asleep_ == 0 && state_.settings.planes_in_place) {
      dense_plane_forces(pl, v);
      continue;
    }
    plane_contacts(pl);
    pl.slot.touched = !pl.near.empty();
    if (pl.near.empty()) continue;
    subset_.gather(p, pl.near, pl.slot.hist, pl.slot.history);
    const Real normal[3] = {Real(pl.wall.normal[0]), Real(pl.wall.normal[1]), Real(pl.wall.normal[2])};
    const Real velocity[3] = {Real(pl.wall.velocity[0]), Real(pl.wall.velocity[1]), Real(pl.wall.velocity[2])};
    subset_.plane_records(pl.slot.overlap, normal, velocity);
    const Particles<Real> sv = subset_.particles(v);
    WallContacts<Real> sw = subset_.walls();
    sw.gap = Real(law_range(pl.wall.law));
    subset_forces(pl.wall.law, sv, sw);
    subset_.scatter(p, pl.slot.overlap, pl.slot.hist);
    if (asleep_ > 0)  // only a moving wall lists sleeping particles: it wakes those it touches
      for (std::uint32_t i : pl.near)
        if (p.mobile[i] == 0 && pl.slot.overlap[i] > 0) wake(i);
  }
  lap(&StepProfile::planes);
  for (auto &ge : state_.geometries) {
    // searched again when the geometry may have moved by a skin (the search does not change results)
    if (!ge.near_valid || ge.speed * (state_.time - ge.near_since) > state_.skin) find_near_geometry(ge);
    geometry_forces(ge, v);
    ge.slot.touched = true;
  }
  lap(&StepProfile::geometries);
}

// The particles that may touch a geometry until it is searched again: those a sphere 3 skins larger
// touches now. Until the next list build a particle moves at most 1 skin from where it was at the
// last build (kick_and_drift), so at most 2 from where it was at the search; the geometry is searched
// again once it may have moved 1 skin (its fastest surface speed x time). A geometry that gives no
// bound on its speed is evaluated for every particle.
template <class Real> void Simulation<Real>::find_near_geometry(GeometrySlot<Real> &ge) {
  auto &p = state_.particles;
  const std::size_t n = p.size();
  ge.near.clear();
  ge.near_valid = false;
  const auto *ops = ge.geometry.ops;
  const double speed = ops->max_surface_speed ? ops->max_surface_speed(ge.geometry.self) : inf;
  if (n == 0 || !(state_.skin > 0) || !(speed >= 0 && speed < inf)) return;
  const Real margin = Real(3 * state_.skin);
  inflated_radius_.resize(n);
  parallel_for(this_thread_team(), n, [&](long long i) { inflated_radius_[i] = p.r[i] + margin; });
  Particles<Real> v = view();
  v.r = inflated_radius_.data();
  v.t = Real(state_.time + ge.geometry.time_shift);
  WallContacts<Real> w = ge.slot.view(n);
  if constexpr (std::is_same_v<Real, double>) ops->contacts_f64(ge.geometry.self, &v, &w);
  else ops->contacts_f32(ge.geometry.self, &v, &w);
  for (std::size_t i = 0; i < n; ++i)
    if (w.overlap[i] > 0) ge.near.push_back(static_cast<std::uint32_t>(i));
  std::fill(ge.slot.overlap.begin(), ge.slot.overlap.end(), Real(0));
  if (ge.slot.history) {  // far particles touch nothing: no history (the law cleared it when they left)
    std::size_t k = 0;
    for (std::size_t i = 0; i < n; ++i) {
      if (k < ge.near.size() && ge.near[k] == i) {
        ++k;
        continue;
      }
      std::fill_n(ge.slot.hist.begin() + i * ge.slot.history, ge.slot.history, Real(0));
    }
  }
  ge.near_valid = true;
  ge.near_since = state_.time;
  ge.speed = speed;
}

// Contacts and forces of one geometry, over its near particles only when they are known.
template <class Real> void Simulation<Real>::geometry_forces(GeometrySlot<Real> &ge, const Particles<Real> &v) {
  auto &p = state_.particles;
  const auto *ops = ge.geometry.ops;
  const ContactLaw &law = ge.geometry.law;
  auto evaluate = [&](const Particles<Real> &pv, WallContacts<Real> &w) {
    Particles<Real> at = pv;  // the geometry's own clock
    at.t = Real(state_.time + ge.geometry.time_shift);
    if constexpr (std::is_same_v<Real, double>) {
      ops->contacts_f64(ge.geometry.self, &at, &w);
      law.ops->walls_f64(law.self, &pv, &w);
    } else {
      ops->contacts_f32(ge.geometry.self, &at, &w);
      law.ops->walls_f32(law.self, &pv, &w);
    }
  };
  if (!ge.near_valid) {
    WallContacts<Real> w = ge.slot.view(p.size());
    evaluate(v, w);
    if (asleep_ > 0)
      for (std::uint32_t i = 0; i < p.size(); ++i)
        if (ge.slot.overlap[i] > 0) wake(i);
    return;
  }
  if (ge.near.empty()) return;
  subset_.gather(p, ge.near, ge.slot.hist, ge.slot.history);
  const Particles<Real> sv = subset_.particles(v);
  WallContacts<Real> sw = subset_.walls();
  {
    const TeamSizeScope serial(sw.n < subset_parallel_from ? 1 : 0);  // a team would cost more than the work
    evaluate(sv, sw);
  }
  subset_.scatter(p, ge.slot.overlap, ge.slot.hist);
  if (asleep_ > 0)  // a moving surface wakes what it touches
    for (std::uint32_t i : ge.near)
      if (ge.slot.overlap[i] > 0) wake(i);
}

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
  const PairList<Real> l = state_.list.view();  // its upper entries, when the list keeps them
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
  const Real x_max = Real(sleep_x_max_);
  const std::uint32_t needed = state_.settings.sleep_checks;
  std::uint32_t fell = 0;
  const std::size_t n = p.size();
  run_team(this_thread_team(), [&](TeamSlot team) {
    std::uint32_t mine = 0;
    const auto [lo, hi] = team_share(n, team);
    for (std::size_t ii = lo; ii < hi; ++ii) {
      const auto i = static_cast<std::uint32_t>(ii);
      if (p.mobile[i] == 0) continue;
      const bool rest = p.x[i] < x_max && !fast(i);
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
