// The run report's sections, each from the run directory's files alone; a section whose files are not
// there yet comes back with an empty body.
#pragma once
#include <nlohmann/json.hpp>

#include "workflow/report/report_parts.hpp"

namespace spreadmap::report {

Section answer_section(const fs::path &run);  // the optimum of each target, its probability, map.png
Section scene_section(const nlohmann::json &manifest);
Section cases_section(const fs::path &run, const nlohmann::json &manifest);  // with metrics and snapshots
Section surrogates_section(const fs::path &run);  // Table 4 form, trust verdicts, parity plots
Section map_section(const fs::path &run);         // response surfaces
Section verify_section(const fs::path &run);
Section provenance_section(const fs::path &run, const nlohmann::json &manifest);

}  // namespace spreadmap::report
