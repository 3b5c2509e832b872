// What a layer-by-layer case (layers.hpp: heaps lifted onto the bed; machine_layers.hpp: a machine)
// shares: a finished layer read back, and case.json assembled from its layers' records.
#pragma once
#include <filesystem>
#include <nlohmann/json_fwd.hpp>
#include <optional>
#include <string>

#include "engine/particle_set.hpp"
#include "workflow/cases/case_runner.hpp"

namespace spreadmap {

// The end state of layer `dir` when it finished before (its layer.json sealed with this `hash`):
// read back, never recomputed. nullopt otherwise.
std::optional<engine::ParticleSet> finished_layer(const std::filesystem::path &dir, const std::string &hash,
                                                  const std::string &name);

// The case's state.vtp (the last layer's, byte for byte) and its case.json: the layers' records, the
// spheres removed and the steps over all of them (removed, removed_settling, removed_strokes), the last
// layer's time, speed and spreader. `extra` (particles_start, particles_end, ...) is merged in.
nlohmann::json finish_layered_case(const CaseRequest &req, const std::string &hash, const nlohmann::json &layers,
                                   const nlohmann::json &extra);

}  // namespace spreadmap
