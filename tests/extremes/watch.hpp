// Runs a scene while watching it: every `every` steps the physical truths of checks.hpp are measured
// on the state and the worst values kept, with the mechanical energy sampled for the growth checks.
// A RunError or SetupError from the engine ends the run and is kept as text, so a test can assert
// that a legitimate scene was not stopped, or that an unstable one was, and with what message.
#pragma once
#include <string>
#include <vector>

#include "extremes/checks.hpp"

namespace spreadmap::extremes {

struct EnergySample {
  double t;
  Energy e;
};

struct Watch {
  double worst_substrate = -1;    // deepest substrate overlap / diameter seen
  double worst_roller = -1;       // deepest roller overlap / diameter seen
  std::size_t roller_inside = 0;  // sphere centres found inside the roller, summed over samples
  double top_speed = 0;           // fastest sphere seen [m/s]
  std::string non_finite;         // the first non-finite particle seen, "" if none
  std::string stopped;            // the engine's error message if it stopped the run, "" if not
  std::vector<EnergySample> energy;

  // Largest energy at or after t_from, relative to the first sample at or after t_from (1 = no growth).
  double energy_growth_after(double t_from) const;
  // First and last energy sample at or after t_from.
  Energy first_energy_after(double t_from) const;
  Energy last_energy() const { return energy.empty() ? Energy{} : energy.back().e; }
};

Watch run_watched(Scene &scene, double t_end, unsigned every = 200);

}  // namespace spreadmap::extremes
