// Simulation's forces: the pair law over the list, the plane walls and the geometries (spreaders).
#include <engine/cell_grid.hpp>
#include <engine/contact_loops.hpp>
#include <engine/history_values.hpp>
#include <engine/errors.hpp>
#include <engine/simulation.hpp>
#include <engine/neighbour_listing.hpp>
#include <engine/stability.hpp>
#include <engine/team_size_scope.hpp>
#include <engine/thread_team.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

namespace spreadmap::engine {

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
      const bool held = any_value(s.hist.data() + i * history, history);
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
  WallContacts<Real> w = s.view(n);
  w.gap = Real(range);
  const bool in_run = takes_ranges(plane.wall.law);  // the law on each thread's part, in the same run
  std::uint32_t touching = 0;
  run_team(this_thread_team(), [&](TeamSlot team) {
    const auto [lo, hi] = team_share(n, team);
    std::uint32_t mine = 0;
    with_simd([&] {
      mine = plane_overlaps(point, normal, p.x.data(), p.y.data(), p.z.data(), p.r.data(), s.overlap.data(), lo, hi,
                            floor);
    });
    // apart: the law still runs for a particle that holds history from this plane, to clear it
    for (std::size_t i = lo; i < hi && history > 0; ++i)
      mine += s.overlap[i] > floor || !any_value(s.hist.data() + i * history, history) ? 0u : 1u;
    // a part where nothing touches or holds history: the law would find nothing to do in it
    if (in_run && mine > 0) wall_forces_range(plane.wall.law, view, w, std::uint32_t(lo), std::uint32_t(hi));
#pragma omp atomic
    touching += mine;
  });
  s.touched = touching > 0;
  if (s.touched && !in_run) wall_forces(plane.wall.law, view, w);
}

// One wall's law over a subset of particles gathered beforehand, then the forces added back. A small
// subset runs on this thread: a team would cost more than the work.
template <class Real>
void Simulation<Real>::subset_forces(const ContactLaw &law, const Particles<Real> &sv, WallContacts<Real> &sw) {
  const TeamSizeScope serial(sw.n < subset_parallel_from ? 1 : 0);
  wall_forces(law, sv, sw);
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
  for (auto &ge : state_.geometries) {
    // searched again when the geometry may have moved by a skin (the search does not change results)
    if (!ge.near_valid || ge.speed * (state_.time - ge.near_since) > state_.skin) find_near_geometry(ge);
  }
  // The geometries' copies are evaluated in the pair loop, each thread for the particles whose pairs it
  // sweeps: a spreader touches a few hundred particles, too few to share in a run of their own.
  bool copies = false;
  for (auto &ge : state_.geometries)
    if (geometry_copied(ge)) {
      ge.copy.size_for(ge.near, ge.slot.history);
      copies = true;
    }
  struct Copying {
    Simulation *sim;
    const Particles<Real> *v;
    double seconds;  // on the thread with the first particles, as the profile times the step
  } copying{this, &v, 0};
  const PairSideJob side{[](void *arg, std::uint32_t lo, std::uint32_t hi) {
                           auto *c = static_cast<Copying *>(arg);
                           const auto began = std::chrono::steady_clock::now();
                           for (auto &ge : c->sim->state_.geometries)
                             if (c->sim->geometry_copied(ge)) c->sim->copy_geometry_forces(ge, *c->v, lo, hi);
                           if (lo == 0 && hi > 0)
                             c->seconds +=
                                 std::chrono::duration<double>(std::chrono::steady_clock::now() - began).count();
                         },
                         &copying};
  pair_forces(state_.pair_law, v, state_.list.view(), copies ? side : PairSideJob{});
  lap(&StepProfile::pairs);  // with the zeroing of the forces above
  if (prof) {                // the geometries' copies are theirs
    prof->pairs -= copying.seconds;
    prof->geometries += copying.seconds;
  }

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
    if (!geometry_copied(ge)) geometry_forces(ge, v);
    else if (!ge.near.empty()) add_geometry_forces(ge);
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
  constexpr double inf = std::numeric_limits<double>::infinity();
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
  geometry_contacts(ge.geometry, v, w);
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

// Whether a geometry's forces are evaluated on a copy of its near particles, each thread for its own
// particles inside the pair loop's run (copy_geometry_forces), and added after the planes'
// (add_geometry_forces).
template <class Real> bool Simulation<Real>::geometry_copied(const GeometrySlot<Real> &ge) const {
  return ge.near_valid && takes_ranges(ge.geometry) && takes_ranges(ge.geometry.law);
}

// The contacts and forces of a geometry's near particles among [lo, hi), into its copy (sized
// beforehand): reads the particles' state and the geometry's own records, writes only its part of the
// copy, so that it may run while the pair loop runs, each thread for its own particles.
template <class Real>
void Simulation<Real>::copy_geometry_forces(GeometrySlot<Real> &ge, const Particles<Real> &v, std::uint32_t lo,
                                            std::uint32_t hi) {
  const auto first = static_cast<std::uint32_t>(std::lower_bound(ge.near.begin(), ge.near.end(), lo) - ge.near.begin());
  const auto last = static_cast<std::uint32_t>(std::lower_bound(ge.near.begin(), ge.near.end(), hi) - ge.near.begin());
  if (first == last) return;
  auto &c = ge.copy;
  c.gather(state_.particles, ge.slot.hist, first, last);
  const Particles<Real> cv = c.particles(v);
  Particles<Real> at = cv;  // the geometry's own clock
  at.t = Real(state_.time + ge.geometry.time_shift);
  WallContacts<Real> cw = c.walls();
  geometry_contacts_range(ge.geometry, at, cw, first, last);
  wall_forces_range(ge.geometry.law, cv, cw, first, last);
}

// The copy's forces added to the particles, its records written back, in the order of the step's sums
// (pairs, planes, geometries).
template <class Real> void Simulation<Real>::add_geometry_forces(GeometrySlot<Real> &ge) {
  ge.copy.scatter(state_.particles, ge.slot.overlap, ge.slot.hist);
  wake_touched(ge);
}

// A moving surface wakes what it touches.
template <class Real> void Simulation<Real>::wake_touched(const GeometrySlot<Real> &ge) {
  if (asleep_ == 0) return;
  auto &p = state_.particles;
  if (!ge.near_valid) {
    for (std::uint32_t i = 0; i < p.size(); ++i)
      if (ge.slot.overlap[i] > 0) wake(i);
    return;
  }
  for (std::uint32_t i : ge.near)
    if (ge.slot.overlap[i] > 0) wake(i);
}

// Contacts and forces of one geometry whose plugins take whole lists only, or whose near particles are
// not known (every particle evaluated).
template <class Real> void Simulation<Real>::geometry_forces(GeometrySlot<Real> &ge, const Particles<Real> &v) {
  auto &p = state_.particles;
  const ContactLaw &law = ge.geometry.law;
  auto evaluate = [&](const Particles<Real> &pv, WallContacts<Real> &w) {
    Particles<Real> at = pv;  // the geometry's own clock
    at.t = Real(state_.time + ge.geometry.time_shift);
    geometry_contacts(ge.geometry, at, w);
    wall_forces(law, pv, w);
  };
  if (!ge.near_valid) {
    WallContacts<Real> w = ge.slot.view(p.size());
    evaluate(v, w);
  } else if (!ge.near.empty()) {
    ge.copy.gather(p, ge.near, ge.slot.hist, ge.slot.history);
    const Particles<Real> cv = ge.copy.particles(v);
    WallContacts<Real> cw = ge.copy.walls();
    {
      const TeamSizeScope serial(cw.n < subset_parallel_from ? 1 : 0);  // a team would cost more than the work
      evaluate(cv, cw);
    }
    ge.copy.scatter(p, ge.slot.overlap, ge.slot.hist);
  }
  wake_touched(ge);
}

template class Simulation<double>;
template class Simulation<float>;

}  // namespace spreadmap::engine
