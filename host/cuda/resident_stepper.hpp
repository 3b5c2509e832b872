// The CUDA backend of the engine (engine/step_backend.hpp): the particle state, the neighbour list
// and the wall records live in device memory for the whole run; each step runs as kernels and the
// host copy is written only when the host reads it (output, checkpoints, error reports).
//
// Nothing of the physics is written twice. Integration runs the engine's half_kick / drift /
// too_fast (engine/kick_drift.hpp), binning the CellGrid and neighbour_ranges the CPU bins with, the
// list the CPU's list_neighbours and carry_history (engine/neighbour_listing.hpp), plane contacts
// plane_overlap, and the forces are the contact and spreader plugins' own CUDA kernels (the same
// SM_HD functors their CPU tables run). Particles are sorted by a stable radix sort on their cell,
// the order of the CPU's stable counting sort, so the list, every particle's order of summation, and
// therefore every bit of the result equal the CPU backend's (tests/gpu: engine_backends_test).
//
// Each stepper runs on its own CUDA stream, so several cases step at once on one GPU, each from its
// own host thread (the simulate stage's pool): a small case no longer leaves the device idle while
// its host thread launches and waits. Each case's kernels and data are its own, so its bits are
// those it has alone (tests/gpu: engine_batch_test).
//
// Not on the GPU: sleeping particles (refused with a clear error). Rare events (removing the
// particles that left the domain, at the list build after they left; a run-time check firing)
// bring the state to the host, are handled there by the engine's own code, and the state goes back.
#pragma once
#include <memory>
#include <utility>
#include <vector>

#include "cuda/plugin_kernels.hpp"
#include "engine/simulation.hpp"

namespace spreadmap::cuda {

// The CUDA kernels of every law and geometry of a Simulation, in the order they were added.
struct ResidentLaws {
  ContactKernels pair;
  std::vector<ContactKernels> planes;                                  // one per plane wall
  std::vector<std::pair<GeometryKernels, ContactKernels>> geometries;  // each geometry and its law
};

// Throws InputError when the settings ask for what the GPU does not do (sleep), RunFailure when the
// device cannot be used.
template <class Real>
std::unique_ptr<engine::StepBackend<Real>> make_resident_stepper(const engine::Simulation<Real> &sim, ResidentLaws laws,
                                                                 int device = 0);

}  // namespace spreadmap::cuda
