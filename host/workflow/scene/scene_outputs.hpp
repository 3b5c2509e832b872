// What `spreadmap simulate` writes at each output time, into the output folder (every file through
// write_atomic_with):
//   state_NNNN.vtp      every particle (centre, velocity, omega, radius, mass, id), for ParaView
//   states.pvd          the collection of the state files with their times (open this one)
//   particles_NNNN.csv  the same as a table: id,x,y,z,vx,vy,vz,wx,wy,wz,radius,mass,fixed (SI)
//   contacts_NNNN.csv   on request: every touching particle pair, id_i,id_j,fx,fy,fz,overlap; the
//                       force on i from j [N] as the contact law gives it in that state
#pragma once
#include <filesystem>
#include <string>
#include <vector>

#include "engine/simulation.hpp"
#include "engine/vtp_io.hpp"

namespace spreadmap::scene {

namespace fs = std::filesystem;

class SceneOutputs {
 public:
  SceneOutputs(fs::path dir, bool particles_csv, bool contacts_csv)
      : dir_(std::move(dir)), particles_csv_(particles_csv), contacts_csv_(contacts_csv) {}
  // Writes output number `series_.size()` of the simulation's current state and updates states.pvd.
  void write(engine::Simulation<double> &sim, const engine::ContactLaw &pair_law);
  std::size_t count() const { return series_.size(); }

 private:
  fs::path dir_;
  bool particles_csv_, contacts_csv_;
  std::vector<engine::SeriesEntry> series_;
};

// Every touching particle pair (i < j in the engine's order) with the force on i from j: the law
// evaluated on the pair alone, from the state and, for a law with history, the pair's stored
// history (a copy: the run is not changed). Such a law advances its history by one step when
// evaluated, so its tangential force is the one of the next step's evaluation; laws without
// history give exactly the force of the step.
struct PairForce {
  std::uint32_t id_i, id_j;
  double f[3];
  double overlap;
};
std::vector<PairForce> pair_forces(engine::Simulation<double> &sim, const engine::ContactLaw &law);

}  // namespace spreadmap::scene
