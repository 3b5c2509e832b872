// The settled heaps of a run, shared by its cases: a heap is settled once per distinct heap_hash()
// (case_runner.hpp) into the run's heaps folder, sealed by the hash of its file, and read back by
// every later case with the same powder, domain, contacts and spreader at rest.
#pragma once
#include "engine/particle_set.hpp"
#include "workflow/cases/case_runner.hpp"

namespace spreadmap {

// The heap of `req` settled, or read back from req.heaps when a case settled it before (and its seal
// still matches). Cases of one heap wait for each other: one settles, the others reuse it.
template <class Real> engine::ParticleSet settled_heap(const Scene &scene, PluginRegistry &reg, const CaseRequest &req);

}  // namespace spreadmap
