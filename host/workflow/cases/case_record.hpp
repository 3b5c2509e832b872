// The record a finished pass leaves in its folder (case.json, or layer.json of a layer) with the
// fingerprint of its state.vtp, and the check a re-run makes of it.
#pragma once
#include <filesystem>
#include <nlohmann/json_fwd.hpp>
#include <string>

#include "engine/particle_set.hpp"

namespace spreadmap {

namespace fs = std::filesystem;

// Writes `record` as dir/RECORD with the fingerprint of dir/state.vtp (what a re-run checks: a state
// damaged or replaced since makes it run again), then removes the pass's checkpoint.
nlohmann::json write_finished_record(const fs::path &dir, const std::string &record_name, nlohmann::json record);

// True when dir/RECORD is a finished result of this hash, its state.vtp intact.
bool record_finished(const fs::path &dir, const std::string &record_name, const std::string &hash);

// What case.json records of a rough substrate: its spheres, their diameter, the mean plane of their
// tops and the R_q of the tops about it.
nlohmann::json substrate_record(const engine::ParticleSet &substrate);

}  // namespace spreadmap
