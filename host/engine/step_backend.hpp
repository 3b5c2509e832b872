// Where a Simulation's steps run. Without a backend the engine steps on the CPU itself. A backend
// (the CUDA one: host/cuda/resident_stepper.hpp) keeps the particle state in its own memory for the
// whole run and steps there, with the same host-device functions for integration, binning and
// neighbour listing, and the plugins' own kernels for the contacts; the host copy is brought up to
// date only when the host reads it (state, arrays, checkpoints, error reports).
//
// One virtual call per step, never per particle or contact.
#pragma once
#include <string>

namespace spreadmap::engine {

template <class Real> class Simulation;

template <class Real> struct StepBackend {
  virtual ~StepBackend() = default;
  virtual std::string name() const = 0;
  // The host copy changed (particles added, a checkpoint loaded, walls switched): take all of it.
  virtual void upload(Simulation<Real> &sim) = 0;
  // One step with the engine's step() semantics (counters and time included).
  virtual void step(Simulation<Real> &sim) = 0;
  // Write the state into the host copy.
  virtual void download(Simulation<Real> &sim) = 0;
};

// A backend's way into the Simulation it steps (the engine's internals, nothing else uses them).
template <class Real> struct StepAccess;

}  // namespace spreadmap::engine
