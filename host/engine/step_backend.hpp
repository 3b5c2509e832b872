// Where a Simulation's steps run. Without a backend the engine steps on the CPU itself. A backend
// (the CUDA one: host/cuda/resident_stepper.hpp) keeps the particle state in its own memory for the
// whole run and steps there, with the same host-device functions for integration, binning and
// neighbour listing, and the plugins' own kernels for the contacts; the host copy is brought up to
// date only when the host reads it (state, arrays, checkpoints, error reports).
//
// A backend sees the Simulation only through the StepState it is handed (engine/step_state.hpp):
// the scene, what a step advances, the step's parameters, and the services on the host copy.
// One virtual call per step, never per particle or contact.
#pragma once
#include <engine/step_state.hpp>

#include <string>

namespace spreadmap::engine {

template <class Real> struct StepBackend {
  virtual ~StepBackend() = default;
  virtual std::string name() const = 0;
  // The host copy changed (particles added, a checkpoint loaded, walls switched): take all of it.
  virtual void upload(StepState<Real> &state) = 0;
  // One step with the engine's step() semantics (time, step, counters and validity flags included);
  // the host copy is stale afterwards (its particles, list and wall slots), until download.
  virtual void step(StepState<Real> &state) = 0;
  // Write the state into the host copy (the same StepState the backend steps).
  virtual void download(StepState<Real> &state) = 0;
};

}  // namespace spreadmap::engine
