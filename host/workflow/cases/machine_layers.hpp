// Layer upon layer on a machine (scene.machine, workflow/spreading/machine_layout.hpp): the feed's
// reservoir filled once (and cached with the run's heaps), then for each layer k the strokes (the
// platform down by the thickness, the piston up by dosing x thickness), the powder settled, and one
// pass of the spreader from behind the feed over the well into the overflow. Layer k is written to
// cases/cNNN/layer_k/ (state.vtp, layer.json) once finished; a re-run reads the finished layers back
// and resumes the one it was on from its checkpoint. The case's state.vtp is the last layer's.
#pragma once
#include <nlohmann/json.hpp>

#include "core/registry.hpp"
#include "workflow/cases/case_runner.hpp"

namespace spreadmap {

// Returns case.json's content.
template <class Real> nlohmann::json spread_machine_layers(const CaseRequest &req, PluginRegistry &reg);

}  // namespace spreadmap
