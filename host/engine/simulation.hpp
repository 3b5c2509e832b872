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
#include <engine/cell_sort.hpp>
#include <engine/counters.hpp>
#include <engine/domain.hpp>
#include <engine/kick_drift.hpp>
#include <engine/neighbour_list.hpp>
#include <engine/particle_arrays.hpp>
#include <engine/particle_set.hpp>
#include <engine/particle_subset.hpp>
#include <engine/settings.hpp>
#include <engine/step_backend.hpp>
#include <engine/team_tuner.hpp>
#include <engine/step_state.hpp>
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
  // Fixed particles (set.fixed) never move: their velocities are zero and they are not integrated;
  // to the particles they touch they weigh fixed_mass_scale times their mass (an immovable body,
  // as a wall is: the contact's reduced mass is the moving particle's to 1e-12). state() reports
  // their own mass. Scenes with fixed particles step on the CPU.
  void add_particles(ParticleSet set, double density = 0);
  static constexpr double fixed_mass_scale = 0x1p40;  // a power of two: the mass comes back exactly
  std::size_t fixed_count() const { return fixed_; }
  // Whether the particle-particle law or a plane's attracts across a gap (steps on the CPU only).
  bool attracts_across_gap() const;
  std::size_t size() const;  // the particles in the domain (arrays() also holds those leaving it)
  // The current state in the engine's current (cell-sorted) order, in double: the particles in the
  // domain (one that left it is removed at the next list build, and is not part of the state).
  ParticleSet state() const;
  const ParticleArrays<Real> &arrays() const {
    sync_host();
    return state_.particles;
  }

  // --- walls ---------------------------------------------------------------------------------
  std::size_t add_plane_wall(PlaneWall wall);       // returns its index; before load_checkpoint
  std::size_t add_geometry(GeometryWall geometry);  // returns its index; before load_checkpoint
  std::size_t plane_wall_count() const { return state_.planes.size(); }
  std::size_t geometry_count() const { return state_.geometries.size(); }
  const PlaneWall &plane_wall(std::size_t i) const { return state_.planes.at(i).wall; }
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
  double time() const { return state_.time; }
  std::uint64_t step_count() const { return state_.step; }

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
  // Particles with x below x_max, or z below z_max, may fall asleep from now on (-infinity, the
  // start: none may): behind a spreader, or buried under the layers above.
  void set_sleep_region(double x_max, double z_max = -std::numeric_limits<double>::infinity()) {
    sleep_x_max_ = x_max;
    sleep_z_max_ = z_max;
  }
  std::size_t sleeping_count() const { return asleep_; }
  // Integrate rotation even when no law makes torque (benchmarks: the cost of what is skipped).
  void force_rotation(bool on);
  void tune_threads(bool on) { state_.settings.tune_threads = on; }  // Settings::tune_threads

  // --- figures -------------------------------------------------------------------------------
  // The particles that left the domain: removed, or to be removed at the next list build (state()
  // leaves those out already).
  std::uint64_t removed_count() const;
  const RunCounters &counters() const { return state_.counters; }
  bool rotation_integrated() const { return state_.rotate; }
  // The neighbour list over arrays()' order: it holds every touching pair of the current state
  // (per-contact outputs evaluate the law on its entries).
  const NeighbourList<Real> &neighbours() const {
    sync_host();
    return state_.list;
  }
  std::size_t list_entries() const {
    sync_host();
    return state_.list.entries();
  }
  double skin() const { return state_.skin; }
  const Domain &domain() const { return state_.domain; }
  const Settings &settings() const { return state_.settings; }

  // --- checkpoints ---------------------------------------------------------------------------
  // Everything a bitwise-identical continuation needs, written atomically (write_atomic).
  // Call between steps. Before load, add the same plane walls and geometries (and particles are
  // replaced by the checkpoint's); mismatched counts, precision or history sizes are SetupErrors.
  void save_checkpoint(const std::filesystem::path &path) const;
  void load_checkpoint(const std::filesystem::path &path);

 private:
  // The host copy is brought up to date before it is read (the pending second half kick run; with a
  // backend, the state downloaded), and marked changed (to be uploaded) before it is written.
  void sync_host() const;
  void host_changes();

  void prepare();
  void resolve_step();
  void rebuild_list();
  void share_like_pairs();  // the step's loops split the particles as the pair loop does
  void find_near_geometry(GeometrySlot<Real> &geometry);
  void geometry_forces(GeometrySlot<Real> &geometry, const Particles<Real> &view);
  bool geometry_copied(const GeometrySlot<Real> &geometry) const;
  void copy_geometry_forces(GeometrySlot<Real> &geometry, const Particles<Real> &view, std::uint32_t lo,
                            std::uint32_t hi);
  void add_geometry_forces(GeometrySlot<Real> &geometry);
  void wake_touched(const GeometrySlot<Real> &geometry);
  void compute_forces(StepProfile *profile = nullptr);  // profile: its parts timed into it
  void plane_contacts(PlaneSlot<Real> &plane);
  void dense_plane_forces(PlaneSlot<Real> &plane, const Particles<Real> &view);
  void subset_forces(const ContactLaw &law, const Particles<Real> &sv, WallContacts<Real> &sw);
  // Wall subsets smaller than this are evaluated on the calling thread.
  static constexpr std::uint32_t subset_parallel_from = 512;
  KickDrift<Real> integration(Real half_dt, Real dt);
  bool kick_and_drift(Real half_dt, Real dt);  // returns true when the list must be rebuilt
  void kick_and_check(Real half_dt);
  void check_overlaps();
  void update_sleep();
  void wake(std::uint32_t i);
  void find_border();
  Particles<Real> view();
  void log(const std::string &message) const;

  // The scene and what a step advances: stepped here (step) or by the backend.
  StepState<Real> state_;
  bool step_resolved_ = false;  // dt, skin, rotation and limits chosen for the current scene
  bool forces_zeroed_ = false;  // kick_and_drift cleared the accumulators after using them
  // The last step's second half kick is still to run: the next kick_and_drift runs it in its pass,
  // sync_host before anything reads or changes the state.
  bool second_kick_pending_ = false;
  std::uint32_t next_id_ = 0;
  // Sleeping: where particles may fall asleep, how many are, and the awake particles listed with a
  // sleeping neighbour (those whose motion can wake one).
  double sleep_x_max_ = -std::numeric_limits<double>::infinity();
  double sleep_z_max_ = -std::numeric_limits<double>::infinity();
  std::size_t asleep_ = 0, asleep_at_build_ = 0;
  // Fixed particles (mobile 0 and 1/m = 0 for good): integrated as sleeping ones are, never woken.
  std::size_t fixed_ = 0;
  std::vector<std::uint32_t> border_;
  // The backend and which copy of the state is newer.
  std::unique_ptr<StepBackend<Real>> backend_;
  mutable bool device_ahead_ = false;  // the backend stepped since the host copy was written
  bool host_changed_ = true;           // the host copy changed since the backend took it

  // Scratch (kept to avoid allocation in rebuilds).
  CellSort cells_;  // the particles sorted into the list's cells
  std::vector<std::uint32_t> scratch_index_;
  std::vector<std::size_t> owner_cuts_;  // see share_like_pairs
  std::vector<Real> scratch_real_;
  std::vector<Real> inflated_radius_;                     // radii + margin for the geometry search
  std::vector<std::vector<std::uint32_t>> thread_index_;  // per-thread index lists
  ParticleSubset<Real> subset_;                           // a plane's particles near it
  TeamTuner tuner_;                                       // how many threads the steps use (Settings::tune_threads)
};

extern template class Simulation<double>;
extern template class Simulation<float>;

}  // namespace spreadmap::engine
