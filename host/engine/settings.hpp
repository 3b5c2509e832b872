// Run settings of a Simulation. SI units.
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>

namespace spreadmap::engine {

struct Settings {
  // Time step [s]. 0 = automatic: dt_safety * critical_dt(). A requested step above critical_dt()
  // is refused (SetupError with both numbers) unless allow_unstable_dt is set.
  double dt = 0;
  // Fraction of the critical step used by the automatic step. dt_crit is about 1 / omega of a
  // contact (stability.hpp), so 0.4 resolves a contact (pi / omega) in about 9 steps at epsilon = 0.8:
  // the usual DEM practice (1/10..1/50 of the contact time) at its coarse end.
  double dt_safety = 0.4;
  // For tests and studies of the stability limit only: accept dt above critical_dt().
  bool allow_unstable_dt = false;

  std::array<double, 3> gravity{0, 0, -9.81};  // [m/s^2]

  // Verlet skin [m]: neighbours are listed up to r_i + r_j + skin; the list is rebuilt when some
  // particle has moved more than skin / 2. 0 = automatic: skin_fraction * largest diameter.
  double skin = 0;
  double skin_fraction = 0.2;

  // Run-time checks, every check_every steps: a pair or wall overlap above overlap_limit times the
  // (smaller) diameter stops the run, and so does any particle faster than speed_limit (0 =
  // automatic: 10 x the fastest physical speed of the scene: free fall across the domain, wall and
  // geometry surface speeds, initial speeds). NaN or infinity is looked for every step.
  double overlap_limit = 0.1;
  double speed_limit = 0;
  std::uint32_t check_every = 10;

  // Laws without history, or whose history mirrors (law_pairs_once): the CPU loop evaluates each
  // touching pair once and gives the other particle the mirror image (engine/pair_loops.hpp). Bitwise
  // the same results as evaluating every list entry for any law whose answer seen from j is the mirror
  // of that seen from i (all laws written with vector operations), and about twice as fast. false:
  // every entry (for tests).
  bool pairs_once = true;

  // While no particle sleeps, plane walls are evaluated over every particle in place (records
  // written where they touch) instead of over a gathered copy of the touching ones: the same bits,
  // no copies, and on every thread. false: always the gathered copy (for tests).
  bool planes_in_place = true;

  // Scenes with fewer particles than this step on one thread: below it, starting the thread team
  // (~20 runs per step) costs more than the work, and on a busy machine much more (measured when
  // the runs were OpenMP regions, dearer than the engine's own team). Results do not
  // depend on it (the engine is deterministic for any thread count). 0: always all threads.
  std::size_t parallel_min_particles = 2000;

  // The thread count of the steps follows measurement (engine/team_tuner.hpp): fewer threads when
  // another process slows one of them down, all of them again when it is gone. Results do not depend
  // on it. false: every step on all threads (benchmarks of a fixed team).
  bool tune_threads = true;

  // Sleeping particles (off by default). A particle in set_sleep_region()'s region (below its x bound,
  // or below its z bound) that is slower than sleep_speed (the surface speed of its spin too) at
  // sleep_checks checks in a row, one every sleep_check_every steps, falls asleep: it is no longer integrated (it stays exactly where it is, at
  // rest), and a pair of two sleeping particles leaves the neighbour list. It wakes when a touching
  // neighbour moves faster than sleep_speed, or a geometry or a moving plane wall touches it. Needs a
  // pair law without history (the tangential springs of two sleeping spheres are not kept).
  bool sleep = false;
  double sleep_speed = 1e-3;  // [m/s]
  std::uint32_t sleep_checks = 10;
  std::uint32_t sleep_check_every = 100;

  // For benchmarks and tests: integrate rotation even when no contact law makes torque.
  bool force_rotation = false;

  // Where the engine says what it decided (rotation skipped, time step chosen). Empty: spdlog::info.
  std::function<void(const std::string &)> log;
};

}  // namespace spreadmap::engine
