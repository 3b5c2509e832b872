// The run report's sections, each from the run directory's files alone; a section whose files are not
// there yet comes back with an empty body.
#pragma once
#include <nlohmann/json_fwd.hpp>

#include "workflow/report/report_parts.hpp"

namespace spreadmap::report {

PageSection answer_section(const fs::path &run);  // the optimum of each target, its probability, map.png
PageSection scene_section(const nlohmann::json &manifest);
PageSection cases_section(const fs::path &run, const nlohmann::json &manifest);  // with metrics and snapshots
PageSection surrogates_section(const fs::path &run);  // Table 4 form, trust verdicts, parity plots
PageSection map_section(const fs::path &run);         // response surfaces
PageSection verify_section(const fs::path &run);
PageSection provenance_section(const fs::path &run, const nlohmann::json &manifest);

}  // namespace spreadmap::report
