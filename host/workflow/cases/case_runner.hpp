// One case of the design: the settled heap (computed once per distinct heap and shared by every
// case that has the same powder, domain, contacts and spreader position: heap_cache.hpp), then the
// spreading run (spread_pass.hpp), with checkpoints every `time.checkpoint_interval` wall-clock
// seconds and a clean stop on SIGINT. Writes state.vtp (+ series/ and series.pvd when snapshots are
// asked for) and case.json (case_record.hpp). With scene.layers.count > 1, each layer's pass in
// layer_K/ (state.vtp, layer.json), the last one's state as the case's state.vtp (layers.hpp).
#pragma once
#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>

#include "core/registry.hpp"
#include "workflow/spreading/scene_model.hpp"

namespace spreadmap {

namespace fs = std::filesystem;

struct CaseRequest {
  std::string id;         // c000
  Scene scene;            // resolved scene of this case (SI)
  nlohmann::json inputs;  // design values of this case (SI)
  fs::path dir;           // cases/c000
  fs::path heaps;         // shared folder of settled heaps
  int threads = 0;        // OpenMP threads for this case (0 = all)
  std::function<void(double fraction, const std::string &detail)> progress;
};

// The hash of everything that decides the case's result (of the scene's JSON form).
std::string case_hash(const Scene &scene);
// The hash of everything that decides the settled heap (the spreader's part as its plugin describes
// itself at rest).
std::string heap_hash(const Scene &scene, PluginRegistry &registry);

// True when the case folder holds a finished result for exactly these inputs, its state.vtp intact
// (the size and hash case.json recorded).
bool case_finished(const fs::path &dir, const std::string &hash);

// The folder of layer k (1-based) of a multi-layer case, inside its case folder: "layer_2".
std::string layer_folder(int layer);

// Runs (or resumes) the case; returns the case.json content. Throws Interrupted on SIGINT/SIGTERM
// after saving a checkpoint, RunFailure when the simulation becomes unstable.
nlohmann::json run_case(const CaseRequest &request, PluginRegistry &registry);

}  // namespace spreadmap
