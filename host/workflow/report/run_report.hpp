// report.html: the whole answer of a run on one self-contained page (images inline, no script, no
// network), for a colleague's browser or an A4 print: the answer first (the optimum and how sure it
// is), then the scene, the cases with their snapshots, the metrics, each surrogate's accuracy, the
// process map, the verification and the provenance. It is a view of the run directory's files,
// rebuilt from them at the end of every stage and by `spreadmap report RUN_DIR`; a section whose
// files are not there yet is left out.
#pragma once
#include <filesystem>

namespace spreadmap {

// Writes <run_dir>/report.html atomically; returns its path. Throws InputError when run_dir holds no
// manifest.json (it is no run directory).
std::filesystem::path write_run_report(const std::filesystem::path &run_dir);

}  // namespace spreadmap
