// StepState<Real>: everything one step of the engine works on, declared once for every stepper. A
// Simulation holds one and steps it on the CPU itself, or hands it to a StepBackend
// (engine/step_backend.hpp), which steps the same state in its own memory.
//
// Who writes what. The Simulation sets up the scene (domain, laws, settings, walls, particles) and
// chooses dt, skin, speed_limit and rotate before a step; a stepper then advances particles, list,
// walls, time, step and counters, exactly as the engine's step() does, and clears or sets the
// validity flags as it rebuilds the list and evaluates forces. A backend that keeps the state in its
// own memory brings these fields up to date before it calls a service below (they work on this copy).
//
// Not thread-safe: one stepper at a time works on a state.
#pragma once
#include <engine/contact_loops.hpp>
#include <engine/counters.hpp>
#include <engine/domain.hpp>
#include <engine/neighbour_list.hpp>
#include <engine/particle_arrays.hpp>
#include <engine/settings.hpp>
#include <engine/wall_slots.hpp>
#include <engine/walls.hpp>

#include <cstdint>
#include <utility>
#include <vector>

namespace spreadmap::engine {

template <class Real> struct StepState {
  StepState(const Domain &scene_domain, ContactLaw scene_pair_law, Settings scene_settings)
      : domain(scene_domain), pair_law(scene_pair_law), settings(std::move(scene_settings)) {}

  // --- the scene ------------------------------------------------------------------------------
  Domain domain;
  ContactLaw pair_law;  // the particle-particle law
  Settings settings;

  // --- what a step advances ---------------------------------------------------------------------
  ParticleArrays<Real> particles;  // in the current (cell-sorted) order
  NeighbourList<Real> list;        // with the pair law's contact history
  std::vector<PlaneSlot<Real>> planes;
  std::vector<GeometrySlot<Real>> geometries;
  double time = 0;         // [s]
  std::uint64_t step = 0;  // steps taken since the start (a resumed run continues the count)
  RunCounters counters;
  // list_valid false: the list must be rebuilt (particles added or removed, the skin changed)
  // before the forces are evaluated; forces_valid false: the forces must be evaluated before a kick.
  bool list_valid = false;
  bool forces_valid = false;
  // Some particle's centre may be outside an open axis: it is removed (remove_escaped) at the next
  // list build, not at once. Until then it moves on and touches only what it touched as it left;
  // removing it at once would rebuild the list of all whenever one leaves (an open-sided plate
  // loses spheres almost every step).
  bool leaving = false;

  // --- the step's parameters, chosen by the Simulation ------------------------------------------
  double dt = 0;           // [s]
  double skin = 0;         // Verlet skin [m]
  double speed_limit = 0;  // a particle faster than this stops the run [m/s]
  bool rotate = false;     // rotation is integrated (some law makes torque)

  // --- services on this copy of the state -------------------------------------------------------
  // Removes the particles whose centre left an open axis (with their wall history), counts them in
  // counters.removed and marks the list invalid when there were some; clears `leaving`.
  void remove_escaped();
  // Whether particle i's centre is outside an open axis (it left the domain), and how many are.
  bool outside(std::size_t i) const;
  std::size_t outside_count() const;
  // The run-time checks' error messages: they throw RunError naming the first offending particle
  // (NaN or infinite, or faster than speed_limit), and the first pair or wall contact deeper than
  // settings.overlap_limit (pairs looked at only when `bad_pairs` > 0: a count found beforehand).
  [[noreturn]] void report_bad_particle() const;
  void report_deep_overlap(std::uint32_t bad_pairs) const;

  // Every wall's slot, planes first; their columns sized to the particles (dense plane records to
  // be written again).
  template <class F> void for_each_wall_slot(F &&f) {
    for (auto &pl : planes) f(pl.slot);
    for (auto &ge : geometries) f(ge.slot);
  }
  void resize_walls();
  // Whether the list keeps mirrors for the CPU loop that evaluates each pair once (law_pairs_once).
  bool pairs_once() const { return settings.pairs_once && law_pairs_once(pair_law); }
};

extern template struct StepState<double>;
extern template struct StepState<float>;

}  // namespace spreadmap::engine
