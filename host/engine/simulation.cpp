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

// Runs the enclosing scope on one thread when asked (small scenes), restoring the caller's thread
// count (the OpenMP setting the thread team follows) on exit, exceptions included. Affects only the
// calling thread's runs.
class SerialScope {
 public:
  explicit SerialScope(bool serial) {
#ifdef _OPENMP
    if (serial && omp_get_max_threads() > 1) {
      saved_ = omp_get_max_threads();
      omp_set_num_threads(1);
    }
#else
    (void)serial;
#endif
  }
  ~SerialScope() {
#ifdef _OPENMP
    if (saved_ > 0) omp_set_num_threads(saved_);
#endif
  }
  SerialScope(const SerialScope &) = delete;
  SerialScope &operator=(const SerialScope &) = delete;

 private:
  int saved_ = 0;
};

void check_law(const ContactLaw &law, const std::string &what) {
  if (!law.ops || !law.ops->natural_frequency || !law.ops->damping_ratio || !law.ops->makes_torque ||
      !law.ops->pairs_f64 || !law.ops->pairs_f32 || !law.ops->walls_f64 || !law.ops->walls_f32)
    throw SetupError(fmt::format("{}: the contact law has no complete ops table (a null function pointer); "
                                 "bind a contact plugin built with this SDK",
                                 what));
}
}  // namespace

template <class Real>
Simulation<Real>::Simulation(const Domain &domain, ContactLaw pair_law, Settings settings)
    : domain_(domain), pair_law_(pair_law), settings_(std::move(settings)) {
  check_law(pair_law_, "particle-particle contact");
  for (int a = 0; a < 3; ++a)
    if (!(domain_.hi[a] > domain_.lo[a]) || !std::isfinite(domain_.lo[a]) || !std::isfinite(domain_.hi[a]))
      throw SetupError(fmt::format("domain: axis {} spans [{}, {}] m; hi must be finite and greater than lo",
                                   "xyz"[a], domain_.lo[a], domain_.hi[a]));
  if (!(settings_.dt >= 0) || !(settings_.dt_safety > 0) || !(settings_.dt_safety <= 1))
    throw SetupError(fmt::format("settings: dt = {} s and dt_safety = {}: need dt >= 0 (0 = automatic) and 0 < "
                                 "dt_safety <= 1",
                                 settings_.dt, settings_.dt_safety));
  if (!(settings_.overlap_limit > 0) || settings_.check_every == 0)
    throw SetupError("settings: overlap_limit must be > 0 and check_every >= 1");
  if (settings_.sleep) {
    if (pair_law_.ops->history > 0)
      throw SetupError("settings: sleep needs a particle-particle law without history (the tangential springs of two "
                       "sleeping spheres would be lost); turn sleep off or use a law without history");
    if (!(settings_.sleep_speed > 0) || settings_.sleep_checks == 0 || settings_.sleep_check_every == 0)
      throw SetupError("settings: sleep needs sleep_speed > 0, sleep_checks >= 1 and sleep_check_every >= 1");
  }
  list_.start.assign(1, 0);
}

template <class Real> void Simulation<Real>::log(const std::string &message) const {
  if (settings_.log) settings_.log(message);
  else spdlog::info("{}", message);
}

template <class Real> void Simulation<Real>::WallSlot::resize(std::size_t n) {
  for (auto *c : {&overlap, &nx, &ny, &nz, &vx, &vy, &vz}) c->resize(n, Real(0));
  hist.resize(n * history, Real(0));
}

template <class Real> template <class F> void Simulation<Real>::for_each_wall_slot(F &&f) {
  for (auto &pl : planes_) f(pl.slot);
  for (auto &g : geometries_) f(g.slot);
}

template <class Real> void Simulation<Real>::resize_walls() {
  const std::size_t n = p_.size();
  for_each_wall_slot([n](WallSlot &s) { s.resize(n); });
  for (auto &pl : planes_) pl.records_for = 0;  // the dense records are written again
}

// ---------------------------------------------------------------------------------------------
// particles and walls

template <class Real> void Simulation<Real>::add_particles(ParticleSet set, double density) {
  host_changes();
  set.validate("add_particles");
  if (set.mass.empty() && !(density > 0))
    throw SetupError("add_particles: the set has no mass column and no density was given; give density [kg/m^3]");
  set.fill_defaults(density, next_id_);
  const std::size_t old_n = p_.size(), n = old_n + set.size();
  if (n >= no_index) throw SetupError("add_particles: more than 4e9 particles");
  p_.resize(n);
  for (std::size_t k = 0; k < set.size(); ++k) {
    double pos[3] = {set.x[k], set.y[k], set.z[k]};
    for (int a = 0; a < 3; ++a) {
      if (domain_.periodic[a]) {
        const double l = domain_.length(a);
        pos[a] = domain_.lo[a] + (pos[a] - domain_.lo[a]) - std::floor((pos[a] - domain_.lo[a]) / l) * l;
        if (pos[a] >= domain_.hi[a]) pos[a] = domain_.lo[a];
      } else if (pos[a] < domain_.lo[a] || pos[a] >= domain_.hi[a]) {
        throw SetupError(fmt::format("add_particles: particle {} (id {}) has {} = {} m, outside the open domain "
                                     "axis [{}, {}) m; move it inside or make the axis periodic",
                                     k, set.id[k], "xyz"[a], pos[a], domain_.lo[a], domain_.hi[a]));
      }
    }
    const std::size_t i = old_n + k;
    p_.x[i] = Real(pos[0]); p_.y[i] = Real(pos[1]); p_.z[i] = Real(pos[2]);
    p_.vx[i] = Real(set.vx[k]); p_.vy[i] = Real(set.vy[k]); p_.vz[i] = Real(set.vz[k]);
    p_.wx[i] = Real(set.wx[k]); p_.wy[i] = Real(set.wy[k]); p_.wz[i] = Real(set.wz[k]);
    p_.r[i] = Real(set.radius[k]);
    p_.m[i] = Real(set.mass[k]);
    p_.inv_m[i] = Real(1.0 / set.mass[k]);
    p_.inv_i[i] = Real(1.0 / (0.4 * set.mass[k] * set.radius[k] * set.radius[k]));
    p_.id[i] = set.id[k];
    p_.list_index[i] = no_index;
    p_.mobile[i] = 1;
    p_.calm[i] = 0;
    next_id_ = std::max(next_id_, set.id[k] + 1);
  }
  resize_walls();
  step_resolved_ = list_valid_ = forces_valid_ = false;
}

template <class Real> ParticleSet Simulation<Real>::state() const {
  sync_host();
  ParticleSet s;
  const std::size_t n = p_.size();
  auto copy = [n](const std::vector<Real> &from, std::vector<double> &to) { to.assign(from.begin(), from.begin() + n); };
  copy(p_.x, s.x); copy(p_.y, s.y); copy(p_.z, s.z);
  copy(p_.vx, s.vx); copy(p_.vy, s.vy); copy(p_.vz, s.vz);
  copy(p_.wx, s.wx); copy(p_.wy, s.wy); copy(p_.wz, s.wz);
  copy(p_.r, s.radius); copy(p_.m, s.mass);
  s.id = p_.id;
  return s;
}

template <class Real> std::size_t Simulation<Real>::add_plane_wall(PlaneWall wall) {
  host_changes();
  check_law(wall.law, "plane wall '" + wall.name + "'");
  const double len = std::sqrt(wall.normal[0] * wall.normal[0] + wall.normal[1] * wall.normal[1] +
                               wall.normal[2] * wall.normal[2]);
  if (!(len > 0) || !std::isfinite(len))
    throw SetupError(fmt::format("plane wall '{}': normal ({}, {}, {}) must be a finite non-zero vector", wall.name,
                                 wall.normal[0], wall.normal[1], wall.normal[2]));
  for (auto &c : wall.normal) c /= len;
  PlaneSlot s;
  s.wall = std::move(wall);
  s.slot.history = s.wall.law.ops->history;
  s.slot.resize(p_.size());
  planes_.push_back(std::move(s));
  step_resolved_ = forces_valid_ = false;
  return planes_.size() - 1;
}

template <class Real> std::size_t Simulation<Real>::add_geometry(GeometryWall geometry) {
  host_changes();
  check_law(geometry.law, "geometry '" + geometry.name + "'");
  if (!geometry.ops || !geometry.ops->contacts_f64 || !geometry.ops->contacts_f32)
    throw SetupError(fmt::format("geometry '{}': no contacts function in its ops table", geometry.name));
  GeometrySlot s;
  s.geometry = std::move(geometry);
  s.slot.history = s.geometry.law.ops->history;
  s.slot.resize(p_.size());
  geometries_.push_back(std::move(s));
  step_resolved_ = forces_valid_ = false;
  return geometries_.size() - 1;
}

template <class Real> void Simulation<Real>::set_plane_wall_active(std::size_t i, bool active) {
  host_changes();
  auto &pl = planes_.at(i);
  if (pl.wall.active == active) return;
  pl.wall.active = active;
  std::fill(pl.slot.hist.begin(), pl.slot.hist.end(), Real(0));
  std::fill(pl.slot.overlap.begin(), pl.slot.overlap.end(), Real(0));
  pl.slot.touched = false;
  forces_valid_ = false;
}

template <class Real>
void Simulation<Real>::set_plane_wall_velocity(std::size_t i, const std::array<double, 3> &velocity) {
  host_changes();
  planes_.at(i).wall.velocity = velocity;
}

// ---------------------------------------------------------------------------------------------
// time step

template <class Real> double Simulation<Real>::critical_dt() const {
  const std::size_t n = p_.size();
  if (n == 0) return inf;
  std::size_t light = 0, heavy = 0;
  for (std::size_t i = 1; i < n; ++i) {
    if (p_.m[i] < p_.m[light]) light = i;
    if (p_.m[i] > p_.m[heavy]) heavy = i;
  }
  const double m[2] = {double(p_.m[light]), double(p_.m[heavy])}, r[2] = {double(p_.r[light]), double(p_.r[heavy])};
  double best = inf;
  if (n >= 2) {
    for (int a = 0; a < 2; ++a)
      for (int b = a; b < 2; ++b)
        best = std::min(best, packing_critical_dt(pair_law_, m[a] * m[b] / (m[a] + m[b]), r[a] * r[b] / (r[a] + r[b])));
  }
  auto wall = [&](const ContactLaw &law) {
    for (int a = 0; a < 2; ++a) best = std::min(best, packing_critical_dt(law, m[a], r[a]));
  };
  for (const auto &pl : planes_) wall(pl.wall.law);
  for (const auto &g : geometries_) wall(g.geometry.law);
  return best;
}

template <class Real> double Simulation<Real>::dt() {
  if (!step_resolved_) resolve_step();
  return dt_;
}

template <class Real> void Simulation<Real>::resolve_step() {
  const double crit = critical_dt();
  if (settings_.dt > 0) {
    if (settings_.dt > crit && !settings_.allow_unstable_dt)
      throw SetupError(fmt::format("time step dt = {:.6g} s is above the critical step dt_crit = {:.6g} s of this "
                                   "scene's contacts (velocity-Verlet with damping, in the densest packing); use "
                                   "dt <= {:.6g} s, or dt: 0 for the automatic {:.3g} x dt_crit = {:.6g} s",
                                   settings_.dt, crit, crit, settings_.dt_safety, settings_.dt_safety * crit));
    dt_ = settings_.dt;
  } else {
    if (!std::isfinite(crit))
      throw SetupError("cannot choose the time step automatically: no particles, or no contact law with a stiffness; "
                       "add particles first or set dt");
    dt_ = settings_.dt_safety * crit;
  }
  double d_max = 0, v_max = 0;
  for (std::size_t i = 0; i < p_.size(); ++i) {
    d_max = std::max(d_max, 2.0 * double(p_.r[i]));
    v_max = std::max(v_max, std::sqrt(double(p_.vx[i]) * p_.vx[i] + double(p_.vy[i]) * p_.vy[i] +
                                      double(p_.vz[i]) * p_.vz[i]));
  }
  skin_ = settings_.skin > 0 ? settings_.skin : settings_.skin_fraction * d_max;
  // The fastest physical speed of the scene: free fall across the domain, moving surfaces, the
  // initial speeds. Ten times that is an explosion, not physics.
  const double g = std::sqrt(settings_.gravity[0] * settings_.gravity[0] + settings_.gravity[1] * settings_.gravity[1] +
                             settings_.gravity[2] * settings_.gravity[2]);
  const double diag = std::sqrt(domain_.length(0) * domain_.length(0) + domain_.length(1) * domain_.length(1) +
                                domain_.length(2) * domain_.length(2));
  double v_phys = std::max(std::sqrt(2 * g * diag), v_max);
  for (const auto &pl : planes_)
    v_phys = std::max(v_phys, std::sqrt(pl.wall.velocity[0] * pl.wall.velocity[0] + pl.wall.velocity[1] * pl.wall.velocity[1] +
                                        pl.wall.velocity[2] * pl.wall.velocity[2]));
  for (const auto &ge : geometries_)
    if (ge.geometry.ops->max_surface_speed) v_phys = std::max(v_phys, ge.geometry.ops->max_surface_speed(ge.geometry.self));
  speed_limit_ = settings_.speed_limit > 0 ? settings_.speed_limit : 10.0 * std::max(v_phys, 1e-3);

  bool torque = settings_.force_rotation || pair_law_.ops->makes_torque(pair_law_.self) != 0;
  for (const auto &pl : planes_) torque = torque || pl.wall.law.ops->makes_torque(pl.wall.law.self) != 0;
  for (const auto &ge : geometries_) torque = torque || ge.geometry.law.ops->makes_torque(ge.geometry.law.self) != 0;
  if (rotate_ != torque || !step_resolved_) {
    if (!torque) log("engine: no contact law makes torque: rotation is not integrated (angular velocities stay as given)");
  }
  rotate_ = torque;
  log(fmt::format("engine: dt = {:.4g} s = {:.3g} x dt_crit (dt_crit = {:.4g} s); skin = {:.3g} m; speed limit {:.3g} m/s",
                  dt_, dt_ / crit, crit, skin_, speed_limit_));
  step_resolved_ = true;
  list_valid_ = false;  // the skin may have changed
}

// ---------------------------------------------------------------------------------------------
// neighbour list

template <class Real> void Simulation<Real>::rebuild_list() {
  const std::size_t n = p_.size();
  ++counters_.list_builds;
  list_valid_ = true;
  if (n == 0) {
    list_.clear();
    list_.start.assign(1, 0);
    return;
  }
  double lo[3] = {inf, inf, inf}, hi[3] = {-inf, -inf, -inf}, r_max = 0;
  {
    Real lx = Real(inf), ly = Real(inf), lz = Real(inf), hx = Real(-inf), hy = Real(-inf), hz = Real(-inf), rm = 0;
    run_team(this_thread_team(), [&](TeamSlot team) {
      Real mine[7] = {Real(inf), Real(inf), Real(inf), Real(-inf), Real(-inf), Real(-inf), 0};
      const auto [lo, hi] = team_share(n, team);
      for (std::size_t i = lo; i < hi; ++i) {
        mine[0] = std::min(mine[0], p_.x[i]); mine[1] = std::min(mine[1], p_.y[i]); mine[2] = std::min(mine[2], p_.z[i]);
        mine[3] = std::max(mine[3], p_.x[i]); mine[4] = std::max(mine[4], p_.y[i]); mine[5] = std::max(mine[5], p_.z[i]);
        mine[6] = std::max(mine[6], p_.r[i]);
      }
#pragma omp critical(spreadmap_bounds)
      {
        lx = std::min(lx, mine[0]); ly = std::min(ly, mine[1]); lz = std::min(lz, mine[2]);
        hx = std::max(hx, mine[3]); hy = std::max(hy, mine[4]); hz = std::max(hz, mine[5]);
        rm = std::max(rm, mine[6]);
      }
    });
    lo[0] = lx; lo[1] = ly; lo[2] = lz; hi[0] = hx; hi[1] = hy; hi[2] = hz; r_max = rm;
  }
  const double reach = 2 * r_max + skin_;
  for (int a = 0; a < 3; ++a)
    if (domain_.periodic[a] && domain_.length(a) < 2 * reach)
      throw SetupError(fmt::format("domain: the periodic length along {} ({:.4g} m) must be at least twice the largest "
                                   "diameter + skin ({:.4g} m); widen the domain or lower the skin",
                                   "xyz"[a], domain_.length(a), reach));
  const CellGrid<Real> grid = make_cell_grid<Real>(domain_, lo, hi, reach, n);
  const std::size_t n_cells = grid.count();

  // Stable counting sort by cell.
  cell_.resize(n);
  parallel_for(this_thread_team(), n, [&](long long i) { cell_[i] = grid.cell_of(p_.x[i], p_.y[i], p_.z[i]); });
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
    p_.for_each_real([&](std::vector<Real> &c) {
      if (&c == &p_.x0 || &c == &p_.y0 || &c == &p_.z0) return;
      if (zero_forces && (&c == &p_.fx || &c == &p_.fy || &c == &p_.fz || &c == &p_.tx || &c == &p_.ty || &c == &p_.tz))
        return;
      gather(c, perm_, scratch_real_);
    });
    p_.for_each_index([&](std::vector<std::uint32_t> &c) { gather(c, perm_, scratch_index_); });
    for_each_wall_slot([&](WallSlot &s) {
      if (s.history) gather(s.hist, perm_, scratch_real_, s.history);
    });
  }
  list_.build(p_, grid, cell_start_, cell_sorted_, domain_, Real(skin_), pair_law_.ops->history, settings_.pairs_once,
              settings_.sleep && asleep_ > 0 ? p_.mobile.data() : nullptr);
  if (settings_.sleep) find_border();
  asleep_at_build_ = asleep_;
  for (auto &ge : geometries_) find_near_geometry(ge);
  parallel_for(this_thread_team(), n, [&](long long i) {
    p_.list_index[i] = static_cast<std::uint32_t>(i);
    p_.x0[i] = p_.x[i]; p_.y0[i] = p_.y[i]; p_.z0[i] = p_.z[i];
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
  if (list_valid_ && list_.pair_owners(threads, owner_cuts_)) team.set_cuts(owner_cuts_.data(), p_.size(), threads);
  else team.set_cuts(nullptr, 0, 0);
}

// ---------------------------------------------------------------------------------------------
// forces

template <class Real> Particles<Real> Simulation<Real>::view() {
  Particles<Real> v;
  v.n = static_cast<std::uint32_t>(p_.size());
  v.x = p_.x.data(); v.y = p_.y.data(); v.z = p_.z.data();
  v.vx = p_.vx.data(); v.vy = p_.vy.data(); v.vz = p_.vz.data();
  v.wx = p_.wx.data(); v.wy = p_.wy.data(); v.wz = p_.wz.data();
  v.r = p_.r.data(); v.m = p_.m.data();
  v.fx = p_.fx.data(); v.fy = p_.fy.data(); v.fz = p_.fz.data();
  v.tx = p_.tx.data(); v.ty = p_.ty.data(); v.tz = p_.tz.data();
  for (int a = 0; a < 3; ++a) {
    v.box_lo[a] = Real(domain_.lo[a]);
    v.box_hi[a] = Real(domain_.hi[a]);
    v.periodic[a] = domain_.periodic[a] ? 1 : 0;
  }
  v.dt = Real(dt_);
  v.t = Real(time_);
  v.team = this_thread_team();
  return v;
}

// The plane's overlap with every particle (kept for the overlap check) and the particles its law
// must see: those touching it and those still holding history from an earlier contact (the law
// clears it), in increasing order.
template <class Real> void Simulation<Real>::plane_contacts(PlaneSlot &plane) {
  const Real point[3] = {Real(plane.wall.point[0]), Real(plane.wall.point[1]), Real(plane.wall.point[2])};
  const Real normal[3] = {Real(plane.wall.normal[0]), Real(plane.wall.normal[1]), Real(plane.wall.normal[2])};
  WallSlot &s = plane.slot;
  const unsigned history = s.history;
  const std::size_t n = p_.size();
  const bool moving = plane.wall.velocity[0] != 0 || plane.wall.velocity[1] != 0 || plane.wall.velocity[2] != 0;
  const int max_threads = max_team_size();
  if (thread_index_.size() < std::size_t(max_threads)) thread_index_.resize(max_threads);
  int teams = 1;
  run_team(this_thread_team(), [&](TeamSlot team) {
    if (team.thread == 0) teams = team.threads;
    auto &mine = thread_index_[team.thread];
    mine.clear();
    const auto [lo, hi] = team_share(n, team);
    for (std::size_t i = lo; i < hi; ++i) {
      const Real overlap = plane_overlap(point, normal, p_.x[i], p_.y[i], p_.z[i], p_.r[i]);
      s.overlap[i] = overlap > 0 ? overlap : Real(0);
      bool held = false;
      for (unsigned h = 0; h < history; ++h) held = held || s.hist[i * history + h] != 0;
      // a sleeping particle on a wall at rest stays as it is: no need to evaluate it
      if ((overlap > 0 || held) && (moving || p_.mobile[i] != 0)) mine.push_back(static_cast<std::uint32_t>(i));
    }
  });
  plane.near.clear();
  for (int t = 0; t < teams; ++t) plane.near.insert(plane.near.end(), thread_index_[t].begin(), thread_index_[t].end());
}

// A plane's law over every particle at once, its records written in place: while no particle
// sleeps, the subset of plane_contacts would only add copies (the substrate touches a good part of
// a heap). A particle apart from the plane gets overlap 0, which the law reads as no contact (it
// clears any history). The normal and velocity records are the same for every particle: written
// when they change, so that a step writes only the overlaps. Same bits as the subset.
template <class Real> void Simulation<Real>::dense_plane_forces(PlaneSlot &plane, const Particles<Real> &view) {
  const Real point[3] = {Real(plane.wall.point[0]), Real(plane.wall.point[1]), Real(plane.wall.point[2])};
  const Real normal[3] = {Real(plane.wall.normal[0]), Real(plane.wall.normal[1]), Real(plane.wall.normal[2])};
  const Real velocity[3] = {Real(plane.wall.velocity[0]), Real(plane.wall.velocity[1]), Real(plane.wall.velocity[2])};
  WallSlot &s = plane.slot;
  const std::size_t n = p_.size();
  const std::array<Real, 6> records{normal[0], normal[1], normal[2], velocity[0], velocity[1], velocity[2]};
  if (plane.records_for != n || plane.records != records) {
    std::vector<Real> *columns[6] = {&s.nx, &s.ny, &s.nz, &s.vx, &s.vy, &s.vz};
    for (int c = 0; c < 6; ++c) std::fill(columns[c]->begin(), columns[c]->end(), records[c]);
    plane.records_for = n;
    plane.records = records;
  }
  const unsigned history = s.history;
  std::uint32_t touching = 0;
  run_team(this_thread_team(), [&](TeamSlot team) {
    const auto [lo, hi] = team_share(n, team);
    std::uint32_t mine = 0;
    with_simd([&] {
      mine = plane_overlaps(point, normal, p_.x.data(), p_.y.data(), p_.z.data(), p_.r.data(), s.overlap.data(), lo, hi);
    });
    // apart: the law still runs for a particle that holds history from this plane, to clear it
    for (std::size_t i = lo; i < hi && history > 0; ++i) {
      bool held = false;
      for (unsigned h = 0; h < history; ++h) held = held || s.hist[i * history + h] != 0;
      mine += s.overlap[i] > 0 || !held ? 0u : 1u;
    }
#pragma omp atomic
    touching += mine;
  });
  s.touched = touching > 0;
  if (!s.touched) return;
  WallContacts<Real> w = s.view(n);
  if constexpr (std::is_same_v<Real, double>) plane.wall.law.ops->walls_f64(plane.wall.law.self, &view, &w);
  else plane.wall.law.ops->walls_f32(plane.wall.law.self, &view, &w);
}

// One wall's law over a subset of particles gathered beforehand, then the forces added back. A small
// subset runs on this thread: a team would cost more than the work.
template <class Real>
void Simulation<Real>::subset_forces(const ContactLaw &law, const Particles<Real> &sv, WallContacts<Real> &sw) {
  const SerialScope serial(sw.n < subset_parallel_from);
  if constexpr (std::is_same_v<Real, double>) law.ops->walls_f64(law.self, &sv, &sw);
  else law.ops->walls_f32(law.self, &sv, &sw);
}

template <class Real> void Simulation<Real>::compute_forces() {
  const std::size_t n = p_.size();
  if (!forces_zeroed_) {
    parallel_for(this_thread_team(), n, [&](long long i) {
      p_.fx[i] = 0; p_.fy[i] = 0; p_.fz[i] = 0;
      p_.tx[i] = 0; p_.ty[i] = 0; p_.tz[i] = 0;
    });
  }
  forces_zeroed_ = false;
  forces_valid_ = true;
  if (n == 0) return;
  const Particles<Real> v = view();
  const PairList<Real> l = list_.view();
  if constexpr (std::is_same_v<Real, double>) pair_law_.ops->pairs_f64(pair_law_.self, &v, &l);
  else pair_law_.ops->pairs_f32(pair_law_.self, &v, &l);

  for (auto &pl : planes_) {
    if (!pl.wall.active) continue;
    if (asleep_ == 0 && settings_.planes_in_place) {
      dense_plane_forces(pl, v);
      continue;
    }
    plane_contacts(pl);
    pl.slot.touched = !pl.near.empty();
    if (pl.near.empty()) continue;
    subset_.gather(p_, pl.near, pl.slot.hist, pl.slot.history);
    const Real normal[3] = {Real(pl.wall.normal[0]), Real(pl.wall.normal[1]), Real(pl.wall.normal[2])};
    const Real velocity[3] = {Real(pl.wall.velocity[0]), Real(pl.wall.velocity[1]), Real(pl.wall.velocity[2])};
    subset_.plane_records(pl.slot.overlap, normal, velocity);
    const Particles<Real> sv = subset_.particles(v);
    WallContacts<Real> sw = subset_.walls();
    subset_forces(pl.wall.law, sv, sw);
    subset_.scatter(p_, pl.slot.overlap, pl.slot.hist);
    if (asleep_ > 0)  // only a moving wall lists sleeping particles: it wakes those it touches
      for (std::uint32_t i : pl.near)
        if (p_.mobile[i] == 0 && pl.slot.overlap[i] > 0) wake(i);
  }
  for (auto &ge : geometries_) {
    // searched again when the geometry may have moved by a skin (the search does not change results)
    if (!ge.near_valid || ge.speed * (time_ - ge.near_since) > skin_) find_near_geometry(ge);
    geometry_forces(ge, v);
    ge.slot.touched = true;
  }
}

// The particles that may touch a geometry until it is searched again: those a sphere 3 skins larger
// touches now. Until the next list build a particle moves at most 1 skin from where it was at the
// last build (kick_and_drift), so at most 2 from where it was at the search; the geometry is searched
// again once it may have moved 1 skin (its fastest surface speed x time). A geometry that gives no
// bound on its speed is evaluated for every particle.
template <class Real> void Simulation<Real>::find_near_geometry(GeometrySlot &ge) {
  const std::size_t n = p_.size();
  ge.near.clear();
  ge.near_valid = false;
  const auto *ops = ge.geometry.ops;
  const double speed = ops->max_surface_speed ? ops->max_surface_speed(ge.geometry.self) : inf;
  if (n == 0 || !(skin_ > 0) || !(speed >= 0 && speed < inf)) return;
  const Real margin = Real(3 * skin_);
  inflated_radius_.resize(n);
  parallel_for(this_thread_team(), n, [&](long long i) { inflated_radius_[i] = p_.r[i] + margin; });
  Particles<Real> v = view();
  v.r = inflated_radius_.data();
  v.t = Real(time_ + ge.geometry.time_shift);
  WallContacts<Real> w = ge.slot.view(n);
  if constexpr (std::is_same_v<Real, double>) ops->contacts_f64(ge.geometry.self, &v, &w);
  else ops->contacts_f32(ge.geometry.self, &v, &w);
  for (std::size_t i = 0; i < n; ++i)
    if (w.overlap[i] > 0) ge.near.push_back(static_cast<std::uint32_t>(i));
  std::fill(ge.slot.overlap.begin(), ge.slot.overlap.end(), Real(0));
  if (ge.slot.history) {  // far particles touch nothing: no history (the law cleared it when they left)
    std::size_t k = 0;
    for (std::size_t i = 0; i < n; ++i) {
      if (k < ge.near.size() && ge.near[k] == i) { ++k; continue; }
      std::fill_n(ge.slot.hist.begin() + i * ge.slot.history, ge.slot.history, Real(0));
    }
  }
  ge.near_valid = true;
  ge.near_since = time_;
  ge.speed = speed;
}

// Contacts and forces of one geometry, over its near particles only when they are known.
template <class Real> void Simulation<Real>::geometry_forces(GeometrySlot &ge, const Particles<Real> &v) {
  const auto *ops = ge.geometry.ops;
  const ContactLaw &law = ge.geometry.law;
  auto evaluate = [&](const Particles<Real> &pv, WallContacts<Real> &w) {
    Particles<Real> at = pv;  // the geometry's own clock
    at.t = Real(time_ + ge.geometry.time_shift);
    if constexpr (std::is_same_v<Real, double>) {
      ops->contacts_f64(ge.geometry.self, &at, &w);
      law.ops->walls_f64(law.self, &pv, &w);
    } else {
      ops->contacts_f32(ge.geometry.self, &at, &w);
      law.ops->walls_f32(law.self, &pv, &w);
    }
  };
  if (!ge.near_valid) {
    WallContacts<Real> w = ge.slot.view(p_.size());
    evaluate(v, w);
    if (asleep_ > 0)
      for (std::uint32_t i = 0; i < p_.size(); ++i)
        if (ge.slot.overlap[i] > 0) wake(i);
    return;
  }
  if (ge.near.empty()) return;
  subset_.gather(p_, ge.near, ge.slot.hist, ge.slot.history);
  const Particles<Real> sv = subset_.particles(v);
  WallContacts<Real> sw = subset_.walls();
  {
    const SerialScope serial(sw.n < subset_parallel_from);  // a team would cost more than the work
    evaluate(sv, sw);
  }
  subset_.scatter(p_, ge.slot.overlap, ge.slot.hist);
  if (asleep_ > 0)  // a moving surface wakes what it touches
    for (std::uint32_t i : ge.near)
      if (ge.slot.overlap[i] > 0) wake(i);
}

// ---------------------------------------------------------------------------------------------
// integration

// The step's kicks, drift and checks in the form the vectorised loops of kick_drift.hpp take.
template <class Real> KickDrift<Real> Simulation<Real>::integration(Real half_dt, Real dt) {
  KickDrift<Real> k{p_.x.data(), p_.y.data(), p_.z.data(), p_.vx.data(), p_.vy.data(), p_.vz.data(),
                    p_.fx.data(), p_.fy.data(), p_.fz.data(), p_.wx.data(), p_.wy.data(), p_.wz.data(),
                    p_.tx.data(), p_.ty.data(), p_.tz.data(), p_.x0.data(), p_.y0.data(), p_.z0.data(),
                    p_.inv_m.data(), p_.inv_i.data(), p_.mobile.data(), half_dt, dt, {}, {}, {}, {}, {}, rotate_,
                    asleep_ > 0};
  for (int a = 0; a < 3; ++a) {
    k.g[a] = Real(settings_.gravity[a]);
    k.lo[a] = Real(domain_.lo[a]);
    k.hi[a] = Real(domain_.hi[a]);
    k.len[a] = Real(domain_.length(a));
    k.periodic[a] = domain_.periodic[a];
  }
  return k;
}

// First half kick (rotation too) and drift in one pass over memory, preceded in the same pass by
// the last step's second half kick and check when it is pending; the force and torque accumulators
// are cleared once used, so the next evaluation needs no pass of its own. Counts the particles
// outside open axes and the non-finite ones; returns true when the list must be rebuilt: some
// particle moved by half the skin since the last build (LAMMPS' and LIGGGHTS' criterion).
template <class Real> bool Simulation<Real>::kick_and_drift(Real half_dt, Real dt) {
  const std::size_t n = p_.size();
  const KickDrift<Real> k = integration(half_dt, dt);
  const bool second_kick = second_kick_pending_;
  second_kick_pending_ = false;
  const Real limit2 = Real(speed_limit_ * speed_limit_);
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
  if (bad > 0) report_bad_particle();
  if (nonfinite > 0) {
    time_ += dt_;  // report the step being taken
    ++step_;
    report_bad_particle();
  }
  if (escaped > 0) remove_escaped();
  const Real half_skin = Real(0.5 * skin_);
  return escaped > 0 || !(largest <= half_skin * half_skin);
}

template <class Real> void Simulation<Real>::remove_escaped() {
  const std::size_t n = p_.size();
  perm_.clear();
  for (std::size_t i = 0; i < n; ++i) {
    bool inside = true;
    const Real pos[3] = {p_.x[i], p_.y[i], p_.z[i]};
    for (int a = 0; a < 3; ++a)
      if (!domain_.periodic[a]) inside = inside && pos[a] >= Real(domain_.lo[a]) && pos[a] < Real(domain_.hi[a]);
    if (inside) perm_.push_back(static_cast<std::uint32_t>(i));
  }
  const std::size_t removed = n - perm_.size();
  if (removed == 0) return;
  p_.for_each_real([&](std::vector<Real> &c) { gather(c, perm_, scratch_real_); });
  p_.for_each_index([&](std::vector<std::uint32_t> &c) { gather(c, perm_, scratch_index_); });
  for_each_wall_slot([&](WallSlot &s) {
    if (s.history) gather(s.hist, perm_, scratch_real_, s.history);
  });
  resize_walls();
  counters_.removed += removed;
  list_valid_ = false;
}

// Second half kick fused with the per-step sanity check (NaN, speed limit).
template <class Real> void Simulation<Real>::kick_and_check(Real half_dt) {
  const std::size_t n = p_.size();
  const KickDrift<Real> k = integration(half_dt, Real(dt_));
  const Real limit2 = Real(speed_limit_ * speed_limit_);
  std::uint32_t bad = 0;
  run_team(this_thread_team(), [&](TeamSlot team) {
    const auto [lo, hi] = team_share(n, team);
    const std::uint32_t mine = kick_check(k, limit2, lo, hi);
#pragma omp atomic
    bad += mine;
  });
  if (bad > 0) report_bad_particle();
}

template <class Real> void Simulation<Real>::report_bad_particle() const {
  const std::size_t n = p_.size();
  for (std::size_t i = 0; i < n; ++i) {
    const double v = std::sqrt(double(p_.vx[i]) * p_.vx[i] + double(p_.vy[i]) * p_.vy[i] + double(p_.vz[i]) * p_.vz[i]);
    const bool finite = std::isfinite(v) && std::isfinite(double(p_.x[i]) + p_.y[i] + p_.z[i]) &&
                        std::isfinite(double(p_.wx[i]) + p_.wy[i] + p_.wz[i]);
    if (!finite)
      throw RunError(fmt::format("the state became NaN or infinite at t = {:.6g} s (step {}): particle id {} at "
                                 "({:.4g}, {:.4g}, {:.4g}) m; the integration is unstable: use a smaller dt (or "
                                 "dt_safety), or check the contact parameters for a law that returns NaN",
                                 time_, step_, p_.id[i], double(p_.x[i]), double(p_.y[i]), double(p_.z[i])));
    if (!(v <= speed_limit_))
      throw RunError(fmt::format("kinetic energy explodes at t = {:.6g} s (step {}): particle id {} moves at {:.4g} m/s, "
                                 "above the limit {:.4g} m/s (10 x the fastest physical speed of the scene); the "
                                 "integration is unstable or contacts overlap too deeply: use a smaller dt (or "
                                 "dt_safety) or stiffer contacts, or raise settings.speed_limit if this speed is real",
                                 time_, step_, p_.id[i], v, speed_limit_));
  }
  throw RunError(fmt::format("the state became invalid at t = {:.6g} s (step {}); use a smaller dt", time_, step_));
}

template <class Real> void Simulation<Real>::check_overlaps() {
  const std::size_t n = p_.size();
  const Real len[3] = {Real(domain_.length(0)), Real(domain_.length(1)), Real(domain_.length(2))};
  const bool per[3] = {domain_.periodic[0], domain_.periodic[1], domain_.periodic[2]};
  const Real limit = Real(settings_.overlap_limit);
  std::uint32_t bad = 0;
  const Real *x = p_.x.data(), *y = p_.y.data(), *z = p_.z.data(), *r = p_.r.data();
  const PairList<Real> l = list_.view();  // its upper entries, when the list keeps them
  run_team(this_thread_team(), [&](TeamSlot team) {
    std::uint32_t mine = 0;
    if (l.pair_i) {  // the flat sequence of upper pairs: one loop, vectorised
      const std::uint64_t pairs = l.first_pair[n];
      const auto [lo, hi] = team_share(pairs, team);
      with_flags([&]<bool PX, bool PY, bool PZ>() {
        with_simd([&] { mine = deep_overlap_pairs<PX, PY, PZ>(l.pair_i, l.pair_j, lo, hi, x, y, z, r, len, limit); });
      }, per[0], per[1], per[2]);
    } else {
      const auto [lo, hi] = team_share(n, team);
      for (std::size_t i = lo; i < hi; ++i)
        mine += deep_overlaps(static_cast<std::uint32_t>(i), x, y, z, r, l.start, l.nbr, l.upper, len, per, limit);
    }
#pragma omp atomic
    bad += mine;
  });
  report_deep_overlap(bad);
}

// After check_overlaps counted `bad` deep pairs (on either backend): finds the first and stops the run.
template <class Real> void Simulation<Real>::report_deep_overlap(std::uint32_t bad) const {
  const bool per[3] = {domain_.periodic[0], domain_.periodic[1], domain_.periodic[2]};
  auto advice = "the contacts are too soft for the speeds or loads of this scene, or dt is too large: stiffen the "
                "contact law (e.g. a larger v_max or smaller overlap_max for hooke laws), lower the speeds, or use a "
                "smaller dt; settings.overlap_limit sets the limit";
  if (bad > 0) {
    for (std::size_t i = 0; i < p_.size(); ++i)
      for (std::uint32_t k = list_.start[i]; k < list_.start[i + 1]; ++k) {
        const std::uint32_t j = list_.nbr[k];
        const double dx = wrap(double(p_.x[i]) - p_.x[j], domain_.length(0), per[0]),
                     dy = wrap(double(p_.y[i]) - p_.y[j], domain_.length(1), per[1]),
                     dz = wrap(double(p_.z[i]) - p_.z[j], domain_.length(2), per[2]);
        const double overlap = double(p_.r[i]) + p_.r[j] - std::sqrt(dx * dx + dy * dy + dz * dz);
        const double d = 2.0 * std::min(p_.r[i], p_.r[j]);
        if (overlap > settings_.overlap_limit * d)
          throw RunError(fmt::format("overlap too large at t = {:.6g} s (step {}): particles id {} and id {} overlap by "
                                     "{:.4g} m = {:.3g} % of the diameter (limit {:.3g} %); {}",
                                     time_, step_, p_.id[i], p_.id[j], overlap, 100 * overlap / d,
                                     100 * settings_.overlap_limit, advice));
      }
  }
  auto wall_check = [&](const WallSlot &s, const std::string &name) {
    for (std::size_t i = 0; i < p_.size(); ++i) {
      const double d = 2.0 * p_.r[i];
      if (s.overlap[i] > settings_.overlap_limit * d)
        throw RunError(fmt::format("overlap too large at t = {:.6g} s (step {}): particle id {} overlaps {} by {:.4g} m "
                                   "= {:.3g} % of its diameter (limit {:.3g} %); {}",
                                   time_, step_, p_.id[i], name, double(s.overlap[i]), 100 * s.overlap[i] / d,
                                   100 * settings_.overlap_limit, advice));
    }
  };
  for (const auto &pl : planes_)
    if (pl.wall.active) wall_check(pl.slot, "plane wall '" + pl.wall.name + "'");
  for (const auto &ge : geometries_) wall_check(ge.slot, "geometry '" + ge.geometry.name + "'");
}

template <class Real> void Simulation<Real>::prepare() {
  if (!step_resolved_) resolve_step();
  if (!list_valid_) rebuild_list();
  if (!forces_valid_) compute_forces();
}

template <class Real> void Simulation<Real>::set_backend(std::unique_ptr<StepBackend<Real>> backend) {
  sync_host();
  backend_ = std::move(backend);
  device_ahead_ = false;
  host_changed_ = true;
}

template <class Real> void Simulation<Real>::sync_host() const {
  if (second_kick_pending_) {
    auto &self = const_cast<Simulation &>(*this);  // completes the step whose state is read
    self.second_kick_pending_ = false;
    self.kick_and_check(Real(0.5 * dt_));
  }
  if (!backend_ || !device_ahead_) return;
  device_ahead_ = false;  // first: download() reads the host copy's sizes through the accessors
  backend_->download(const_cast<Simulation &>(*this));
}

template <class Real> void Simulation<Real>::host_changes() {
  sync_host();
  host_changed_ = true;
}

template <class Real> void Simulation<Real>::step() {
  if (backend_) {
    if (!step_resolved_) resolve_step();
    if (host_changed_) {
      backend_->upload(*this);
      host_changed_ = false;
    }
    device_ahead_ = true;
    backend_->step(*this);
    return;
  }
  const auto t0 = std::chrono::steady_clock::now();
  const SerialScope serial(p_.size() < settings_.parallel_min_particles);
  prepare();
  struct EqualSharesAfter {
    ~EqualSharesAfter() { this_thread_team_object().set_cuts(nullptr, 0, 0); }
  } equal_shares_after;  // outside a step, nothing is split by this simulation's particles
  share_like_pairs();
  const Real dt = Real(dt_), half = Real(0.5 * dt_);
  const bool rebuild = kick_and_drift(half, dt);
  for (auto &pl : planes_)
    for (int a = 0; a < 3; ++a) pl.wall.point[a] += dt_ * pl.wall.velocity[a];
  time_ += dt_;
  ++step_;
  if (rebuild || !list_valid_) {
    rebuild_list();
    share_like_pairs();
  }
  compute_forces();
  // The second half kick waits for the next step's first, which runs it in the same pass
  // (kick_and_drift), unless the state is read or changed before (sync_host). Sleeping reads the
  // velocities now.
  if (settings_.sleep) kick_and_check(half);
  else second_kick_pending_ = true;
  if (step_ % settings_.check_every == 0) check_overlaps();
  ++counters_.steps;
  counters_.particle_steps += double(p_.size());
  counters_.integrated_particle_steps += double(p_.size() - asleep_);
  if (settings_.sleep) update_sleep();
  counters_.wall_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

template <class Real> void Simulation<Real>::run_steps(std::uint64_t n) {
  for (std::uint64_t k = 0; k < n; ++k) step();
}

template <class Real>
bool Simulation<Real>::run_until(double t_end, const StepCallback &callback, std::uint64_t every) {
  if (every == 0) every = 1;
  while (time_ + 0.5 * dt() < t_end) {
    step();
    if (callback && step_ % every == 0 && !callback(*this)) return false;
  }
  return true;
}

// ---------------------------------------------------------------------------------------------
// sleeping (Settings::sleep)

template <class Real> void Simulation<Real>::force_rotation(bool on) {
  host_changes();
  settings_.force_rotation = on;
  step_resolved_ = false;
}

// The awake particles with a sleeping neighbour in the list: only their motion can wake one.
template <class Real> void Simulation<Real>::find_border() {
  border_.clear();
  if (asleep_ == 0) return;
  for (std::uint32_t i = 0; i < p_.size(); ++i) {
    if (p_.mobile[i] == 0) continue;
    for (std::uint32_t k = list_.start[i]; k < list_.start[i + 1]; ++k)
      if (p_.mobile[list_.nbr[k]] == 0) {
        border_.push_back(i);
        break;
      }
  }
}

template <class Real> void Simulation<Real>::wake(std::uint32_t i) {
  if (p_.mobile[i] != 0) return;
  p_.mobile[i] = 1;
  p_.calm[i] = 0;
  --asleep_;
  // its pairs with other sleeping particles are not listed: list them, and evaluate its forces anew
  list_valid_ = false;
  forces_valid_ = false;
}

// After the second half kick: wake the sleeping particles that a fast neighbour touches; every
// sleep_check_every steps, put to sleep the particles at rest long enough in the sleep region.
template <class Real> void Simulation<Real>::update_sleep() {
  const Real s2 = Real(settings_.sleep_speed * settings_.sleep_speed);
  const Real lx = Real(domain_.length(0)), ly = Real(domain_.length(1)), lz = Real(domain_.length(2));
  const bool px = domain_.periodic[0], py = domain_.periodic[1], pz = domain_.periodic[2];
  auto fast = [&](std::uint32_t i) {
    const Real v2 = p_.vx[i] * p_.vx[i] + p_.vy[i] * p_.vy[i] + p_.vz[i] * p_.vz[i];
    const Real w2 = (p_.wx[i] * p_.wx[i] + p_.wy[i] * p_.wy[i] + p_.wz[i] * p_.wz[i]) * p_.r[i] * p_.r[i];
    return !(v2 < s2) || !(w2 < s2);
  };
  if (list_valid_) {
    std::vector<std::uint32_t> woken;
    for (std::uint32_t i : border_) {
      if (!fast(i)) continue;
      for (std::uint32_t k = list_.start[i]; k < list_.start[i + 1]; ++k) {
        const std::uint32_t j = list_.nbr[k];
        if (p_.mobile[j] != 0) continue;
        const Real dx = wrap(p_.x[i] - p_.x[j], lx, px), dy = wrap(p_.y[i] - p_.y[j], ly, py),
                   dz = wrap(p_.z[i] - p_.z[j], lz, pz), reach = p_.r[i] + p_.r[j];
        if (dx * dx + dy * dy + dz * dz < reach * reach) woken.push_back(j);
      }
    }
    for (std::uint32_t j : woken) wake(j);
  }
  if (step_ % settings_.sleep_check_every != 0) return;
  const Real x_max = Real(sleep_x_max_);
  const std::uint32_t needed = settings_.sleep_checks;
  std::uint32_t fell = 0;
  const std::size_t n = p_.size();
  run_team(this_thread_team(), [&](TeamSlot team) {
    std::uint32_t mine = 0;
    const auto [lo, hi] = team_share(n, team);
    for (std::size_t ii = lo; ii < hi; ++ii) {
      const auto i = static_cast<std::uint32_t>(ii);
      if (p_.mobile[i] == 0) continue;
      const bool rest = p_.x[i] < x_max && !fast(i);
      p_.calm[i] = rest ? p_.calm[i] + 1 : 0;
      if (p_.calm[i] < needed) continue;
      p_.mobile[i] = 0;
      p_.vx[i] = 0; p_.vy[i] = 0; p_.vz[i] = 0;
      p_.wx[i] = 0; p_.wy[i] = 0; p_.wz[i] = 0;
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
  if (asleep_ >= asleep_at_build_ + std::max<std::size_t>(1, p_.size() / 20)) list_valid_ = false;
}

template class Simulation<double>;
template class Simulation<float>;

}  // namespace spreadmap::engine
