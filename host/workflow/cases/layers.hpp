// Spreading onto a bed: the layers spread before, or the rough substrate's spheres (layer_feed.hpp).
// A multi-layer case spreads layer k's pass in cases/cNNN/layer_k/ (state.vtp, layer.json).
#pragma once
#include <nlohmann/json.hpp>
#include <string>

#include "core/registry.hpp"
#include "engine/particle_set.hpp"
#include "workflow/cases/case_runner.hpp"

namespace spreadmap {

// Where a pass onto a bed starts (the rough substrate's spheres, or the layers spread before): the
// heap fed onto the bed and settled there under the raised spreader at rest (layer_feed.hpp). When
// the pass will resume from its checkpoint in `dir` (of this `hash`) the settling is skipped: the
// checkpoint replaces the start.
struct BedStart {
  engine::ParticleSet start;
  std::size_t fed = 0;               // the heap's spheres fed onto the bed
  std::size_t removed_settling = 0;  // of those, the ones that left the domain while settling
  bool resumed = false;
};

template <class Real>
BedStart start_on_bed(const Scene &raised, PluginRegistry &reg, const CaseRequest &req, const std::string &name,
                      const fs::path &dir, const std::string &hash, const engine::ParticleSet &bed,
                      const engine::ParticleSet &heap);

// Layer upon layer: each layer's pass written once finished; a re-run skips the finished layers and
// resumes the one it was on. The case's state.vtp is the last layer's. Returns case.json's content.
template <class Real> nlohmann::json spread_layers(const CaseRequest &req, PluginRegistry &reg);

}  // namespace spreadmap
