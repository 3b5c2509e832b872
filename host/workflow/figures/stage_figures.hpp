// The figures each stage leaves in the run directory (snapshot, height map, parity, surfaces, process
// map). Figures are a view of results, never a result: when this build has no VTK, or rendering
// fails, a warning says so once and the stage goes on.
#pragma once
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "analysis/grid.hpp"
#include "analysis/map_trust.hpp"
#include "analysis/optimum.hpp"
#include "analysis/report.hpp"
#include "engine/particle_set.hpp"
#include "workflow/spreading/scene_model.hpp"

namespace spreadmap::figures {

namespace fs = std::filesystem;

bool available();
// A PNG written whole: its signature first and its IEND chunk last (a missing, torn or foreign file is
// not). Stages redraw a figure that is not.
bool whole_png(const fs::path &png);

// "c004: U = 70 mm/s, omega = 0 rad/s" from a case's design inputs (SI), for figure titles.
std::string case_title(const std::string &id, const nlohmann::json &inputs);

// The particles with the spreader drawn as the case recorded it: `record` is case.json (its
// `spreader` describes the body, its `spreader_end` is the pose where it stopped), `pose` a series
// entry's pose instead (null: spreader_end). A record without them (written by an older version)
// draws no spreader. `scene` is the case's resolved scene. Sizes and vector copies follow the
// stage's style (figure_style.hpp).
void snapshot(const engine::ParticleSet &p, const Scene &scene, const nlohmann::json &record, const fs::path &png,
              const std::string &title, const nlohmann::json &pose = nullptr);
// Numbered frames dir/frame_0000.png ... of a snapshot series, one colour scale for all; returns how many.
std::size_t frames(const std::vector<engine::ParticleSet> &states, const std::vector<nlohmann::json> &poses,
                   const Scene &scene, const nlohmann::json &record, const fs::path &dir, const std::string &title);
// A height map as a metrics plugin gives it: nx x ny heights [m] above the substrate, row-major
// (iy * nx + ix), square cells of `cell` from the corner (x0, y0).
struct HeightGrid {
  std::uint32_t nx = 0, ny = 0;
  double x0 = 0, y0 = 0, cell = 0;
  const std::vector<double> &height;
};
void heightmap(const HeightGrid &layer, const fs::path &png, const std::string &title);
// Predicted against simulated V_s and R_q: the training fit, the test rows and, from `cv` (cv.csv:
// <out>_true, <out>_cv), the out-of-fold predictions of cross-validation.
void parity(const analysis::Report &report, const analysis::Table &cv, const std::vector<std::string> &outputs,
            const fs::path &png);
// A response surface over (U, omega) for each output, with the simulated cases as points.
// u_col / omega_col: the grid's input columns; points: rows of (U, omega, outputs...) from training.
void surfaces(const analysis::GridMap &grid, const std::vector<std::string> &units, const analysis::Table &data,
              const fs::path &dir);
// The process map: V_s and R_q contours over (U, omega), the frontier, the simulated cases (the
// grid's input columns of `cases`, when it has them) and the first optimum with its probability of
// meeting the target, marked as proposed (verified < 0), verified by simulation (1) or simulated
// outside its interval (0). `trust`: the maps' verdicts; an untrusted field is drawn greyed and said
// so on the figure.
void process_map(const analysis::GridMap &grid, std::size_t vs, std::size_t rq, const analysis::Table &frontier,
                 const std::vector<analysis::Optimum> &optima, const fs::path &png,
                 const analysis::Table &cases = analysis::Table(), int verified = -1,
                 const std::vector<analysis::MapTrust> &trust = {});

// The speed-accuracy trade: |error| of each fidelity against the reference over its wall time.
struct TradeoffRow {
  std::string name;
  double wall_seconds = 0, vs_error_percent = 0, rq_error_percent = 0;
  bool reference = false;
};
void tradeoff(const std::vector<TradeoffRow> &rows, double vs_scatter_percent, double rq_scatter_percent,
              const fs::path &png);

}  // namespace spreadmap::figures
