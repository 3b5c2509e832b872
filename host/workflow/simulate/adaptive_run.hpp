// design: adaptive in the simulate stage. The design's grid is the set of allowed settings; a few
// space-filling cases run first, then a Gaussian process is fitted to their V_s and R_q after each
// case and the setting where it is least sure runs next, until the cross-validated error reaches
// `target_nrmse` or `budget` cases have run (analysis/adaptive.hpp). Case ids are the grid's row
// numbers, so an interrupted design resumes from its finished cases. Writes adaptive.json.
// With `fidelity:` (two fidelities, analysis/multifidelity.hpp) the cheap cases are the same rows
// with the cheap keys set, ids after the candidates', and every case gets a `fidelity` input (0
// cheap, 1 expensive) that train fits and map holds at 1. The loop's GP learns one noise level per
// fidelity (surrogate/gp's noise_by_input); a train stage asks for it with `params: {noise_by_input: K}`.
#pragma once
#include "workflow/simulate/design.hpp"
#include "workflow/stage/stage.hpp"

namespace spreadmap {

void run_adaptive_design(StageContext &ctx, const Design &design, bool render);

}  // namespace spreadmap
