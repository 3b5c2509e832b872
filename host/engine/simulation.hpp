// Simulation<Real>: the DEM engine for spheres (Real = double by default; float is available and
// measured). Velocity-Verlet translation and rotation, gravity, periodic or open axes, plane walls
// and geometry plugins, Verlet neighbour lists over cell-sorted particles, contact history,
// automatic time step from the contact laws, run-time sanity checks, bitwise checkpoints.
//
// One step (the LAMMPS/LIGGGHTS order): half kick with the last forces, drift, remove particles that
// left through an open face, rebuild the neighbour list if needed, evaluate forces with the
// half-step velocities, half kick. Everything is deterministic: results are bitwise identical run
// to run, for any number of threads, and across a checkpoint/resume.
//
// Thread safety: one Simulation is driven by one thread (it runs its loops on that thread's team,
// engine/thread_team.hpp); distinct Simulations may run concurrently if the plugins' bound instances
// allow it.
#pragma once
#include <engine/counters.hpp>
#include <engine/domain.hpp>
#include <engine/kick_drift.hpp>
#include <engine/neighbour_list.hpp>
#include <engine/particle_arrays.hpp>
#include <engine/particle_set.hpp>
#include <engine/particle_subset.hpp>
#include <engine/settings.hpp>
#include <engine/step_backend.hpp>
#include <engine/walls.hpp>

#include <array>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <vector>

namespace spreadmap::engine {

template <class Real = double> class Simulation {
 public:
  // Called by run_until every `every` steps; return false to stop (SIGINT, time budget...).
  using StepCallback = std::function<bool(const Simulation &)>;

  // pair_law: the particle-particle law; its ops and bound instance must outlive the Simulation.
  Simulation(const Domain &domain, ContactLaw pair_law, Settings settings = {});

  // --- particles -----------------------------------------------------------------------------
  // Adds particles (validated; empty optional columns filled: zero velocities, masses from density
  // when `mass` is empty, fresh ids when `id` is empty). Periodic coordinates are wrapped; a centre
  // outside an open axis is an error. The time step is chosen again before the next step.
  void add_particles(ParticleSet set, double density = 0);
  std::size_t size() const { return p_.size(); }
  // The current state in the engine's current (cell-sorted) order, in double.
  ParticleSet state() const;
  const ParticleArrays<Real> &arrays() const {
    sync_host();
    return p_;
  }

  // --- walls ---------------------------------------------------------------------------------
  std::size_t add_plane_wall(PlaneWall wall);       // returns its index; before load_checkpoint
  std::size_t add_geometry(GeometryWall geometry);  // returns its index; before load_checkpoint
  std::size_t plane_wall_count() const { return planes_.size(); }
  std::size_t geometry_count() const { return geometries_.size(); }
  const PlaneWall &plane_wall(std::size_t i) const { return planes_.at(i).wall; }
  void set_plane_wall_active(std::size_t i, bool active);  // deactivating clears its history
  void set_plane_wall_velocity(std::size_t i, const std::array<double, 3> &velocity);

  // --- time ----------------------------------------------------------------------------------
  // dt_crit: the smallest stable step over the contact types present, in the densest packing
  // (packing_critical_dt): the pair law for the lightest and heaviest particle combinations (when
  // there are >= 2 particles), every wall and geometry law against the lightest and heaviest
  // particle (m_eq = m). See stability.hpp. +inf when none.
  double critical_dt() const;
  // The step in use (resolves the automatic step, or checks the requested one, if not done yet).
  double dt();
  double time() const { return time_; }
  std::uint64_t step_count() const { return step_; }

  void step();
  void run_steps(std::uint64_t n);
  // Steps until time() reaches t_end (within half a step); calls `callback` after every step whose
  // number is a multiple of `every`. Returns false if the callback asked to stop.
  bool run_until(double t_end, const StepCallback &callback = {}, std::uint64_t every = 1);

  // --- backend --------------------------------------------------------------------------------
  // Steps run on `backend` from now on (nullptr: the CPU). The state moves to it at the next step.
  void set_backend(std::unique_ptr<StepBackend<Real>> backend);
  std::string backend_name() const { return backend_ ? backend_->name() : "cpu"; }

  // --- sleeping (Settings::sleep) --------------------------------------------------------------
  // Particles with x below x_max may fall asleep from now on (-infinity, the start: none may).
  void set_sleep_region(double x_max) { sleep_x_max_ = x_max; }
  std::size_t sleeping_count() const { return asleep_; }
  // Integrate rotation even when no law makes torque (benchmarks: the cost of what is skipped).
  void force_rotation(bool on);

  // --- figures -------------------------------------------------------------------------------
  std::uint64_t removed_count() const { return counters_.removed; }
  const RunCounters &counters() const { return counters_; }
  bool rotation_integrated() const { return rotate_; }
  std::size_t list_entries() const {
    sync_host();
    return list_.entries();
  }
  double skin() const { return skin_; }
  const Domain &domain() const { return domain_; }
  const Settings &settings() const { return settings_; }

  // --- checkpoints ---------------------------------------------------------------------------
  // Everything a bitwise-identical continuation needs, written atomically (write_atomic).
  // Call between steps. Before load, add the same plane walls and geometries (and particles are
  // replaced by the checkpoint's); mismatched counts, precision or history sizes are SetupErrors.
  void save_checkpoint(const std::filesystem::path &path) const;
  void load_checkpoint(const std::filesystem::path &path);

 private:
  friend struct StepAccess<Real>;
  // The host copy is brought up to date before it is read (the pending second half kick run; with a
  // backend, the state downloaded), and marked changed (to be uploaded) before it is written.
  void sync_host() const;
  void host_changes();

  struct WallSlot {
    std::vector<Real> overlap, nx, ny, nz, vx, vy, vz, hist;
    unsigned history = 0;
    bool touched = false;  // some particle touched at the last evaluation
    WallContacts<Real> view(std::size_t n) {
      return {static_cast<std::uint32_t>(n), overlap.data(), nx.data(), ny.data(), nz.data(),
              vx.data(), vy.data(), vz.data(), hist.data()};
    }
    void resize(std::size_t n);
  };
  struct PlaneSlot {
    PlaneWall wall;
    WallSlot slot;
    std::vector<std::uint32_t> near;  // the particles its law sees this step (plane_contacts)
    // The normal and velocity its dense records hold for every particle (dense_plane_forces), and
    // for how many particles; 0: not written.
    std::array<Real, 6> records{};
    std::size_t records_for = 0;
  };
  // A geometry is evaluated only for the particles near it (`near`, ascending), found by asking the
  // plugin which particles a sphere 3 skins larger would touch (see find_near_geometry).
  struct GeometrySlot {
    GeometryWall geometry;
    WallSlot slot;
    std::vector<std::uint32_t> near;
    bool near_valid = false;
    double near_since = 0;  // time of the search [s]
    double speed = 0;       // bound on the speed of any surface point [m/s]
  };

  void prepare();
  void resolve_step();
  void rebuild_list();
  void share_like_pairs();  // the step's loops split the particles as the pair loop does
  void find_near_geometry(GeometrySlot &geometry);
  void geometry_forces(GeometrySlot &geometry, const Particles<Real> &view);
  void compute_forces();
  void plane_contacts(PlaneSlot &plane);
  void dense_plane_forces(PlaneSlot &plane, const Particles<Real> &view);
  void subset_forces(const ContactLaw &law, const Particles<Real> &sv, WallContacts<Real> &sw);
  // Wall subsets smaller than this are evaluated on the calling thread.
  static constexpr std::uint32_t subset_parallel_from = 512;
  void remove_escaped();
  KickDrift<Real> integration(Real half_dt, Real dt);
  bool kick_and_drift(Real half_dt, Real dt);  // returns true when the list must be rebuilt
  void kick_and_check(Real half_dt);
  void check_overlaps();
  void report_deep_overlap(std::uint32_t bad) const;
  void update_sleep();
  void wake(std::uint32_t i);
  void find_border();
  [[noreturn]] void report_bad_particle() const;  // throws RunError for the first NaN or too fast particle
  Particles<Real> view();
  void log(const std::string &message) const;
  void resize_walls();
  template <class F> void for_each_wall_slot(F &&f);

  Domain domain_;
  ContactLaw pair_law_;
  Settings settings_;

  ParticleArrays<Real> p_;
  NeighbourList<Real> list_;
  std::vector<PlaneSlot> planes_;
  std::vector<GeometrySlot> geometries_;

  double time_ = 0;
  std::uint64_t step_ = 0;
  double dt_ = 0;
  double skin_ = 0;
  double speed_limit_ = 0;
  bool rotate_ = false;
  bool step_resolved_ = false;  // dt, skin, rotation and limits chosen for the current scene
  bool list_valid_ = false;
  bool forces_valid_ = false;
  bool forces_zeroed_ = false;  // kick_and_drift cleared the accumulators after using them
  // The last step's second half kick is still to run: the next kick_and_drift runs it in its pass,
  // sync_host before anything reads or changes the state.
  bool second_kick_pending_ = false;
  std::uint32_t next_id_ = 0;
  RunCounters counters_;
  // Sleeping: where particles may fall asleep, how many are, and the awake particles listed with a
  // sleeping neighbour (those whose motion can wake one).
  double sleep_x_max_ = -std::numeric_limits<double>::infinity();
  std::size_t asleep_ = 0, asleep_at_build_ = 0;
  std::vector<std::uint32_t> border_;
  // The backend and which copy of the state is newer.
  std::unique_ptr<StepBackend<Real>> backend_;
  mutable bool device_ahead_ = false;  // the backend stepped since the host copy was written
  bool host_changed_ = true;           // the host copy changed since the backend took it

  // Scratch (kept to avoid allocation in rebuilds).
  std::vector<std::uint32_t> perm_, cell_, cell_sorted_, cell_start_, scratch_index_;
  std::vector<std::size_t> owner_cuts_;  // see share_like_pairs
  std::vector<Real> scratch_real_;
  std::vector<Real> inflated_radius_;   // radii + margin for the geometry search
  std::vector<std::vector<std::uint32_t>> thread_index_;  // per-thread index lists
  ParticleSubset<Real> subset_;
};

// The internals a step backend works on. Only a backend uses this.
template <class Real> struct StepAccess {
  using Sim = Simulation<Real>;
  static ParticleArrays<Real> &particles(Sim &s) { return s.p_; }
  static NeighbourList<Real> &list(Sim &s) { return s.list_; }
  static auto &planes(Sim &s) { return s.planes_; }
  static auto &geometries(Sim &s) { return s.geometries_; }
  static const Settings &settings(const Sim &s) { return s.settings_; }
  static const Domain &domain(const Sim &s) { return s.domain_; }
  static const ContactLaw &pair_law(const Sim &s) { return s.pair_law_; }
  static double &time(Sim &s) { return s.time_; }
  static std::uint64_t &step(Sim &s) { return s.step_; }
  static double dt(const Sim &s) { return s.dt_; }
  static double skin(const Sim &s) { return s.skin_; }
  static double speed_limit(const Sim &s) { return s.speed_limit_; }
  static bool rotating(const Sim &s) { return s.rotate_; }
  static bool &list_valid(Sim &s) { return s.list_valid_; }
  static bool &forces_valid(Sim &s) { return s.forces_valid_; }
  static RunCounters &counters(Sim &s) { return s.counters_; }
  static std::size_t asleep(const Sim &s) { return s.asleep_; }
  // Host-side work on the host copy (brought up to date first): removing escaped particles, and the
  // run-time checks' error messages (they throw RunError).
  static void remove_escaped(Sim &s) { s.remove_escaped(); }
  [[noreturn]] static void report_bad_particle(const Sim &s) { s.report_bad_particle(); }
  static void report_deep_overlap(const Sim &s, std::uint32_t bad) { s.report_deep_overlap(bad); }
};

extern template class Simulation<double>;
extern template class Simulation<float>;

}  // namespace spreadmap::engine
