// Off-screen figures of spreadmap (VTK 9.1). Inputs are plain structs in SI units; each function
// converts to display units (mm, mm/s, um, mm^2/s), renders off-screen and writes a PNG of exactly
// options.width x options.height pixels, atomically (the host's write_atomic_with: a temporary
// beside the file, synced and renamed over it; vector copies the same way).
//
// Display: when DISPLAY is unset the first figure starts a private Xvfb (one per process, stopped
// at exit); see offscreen_display.hpp. Figures are rendered one at a time: every function may be
// called from any thread, calls are serialised by an internal mutex.
// Errors: RenderError (a std::runtime_error) with a sentence saying what failed and how to fix it.
#pragma once

#include <array>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

namespace spreadmap::render {

struct RenderError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct Options {
  int width = 1600;   // pixels
  int height = 1000;  // pixels
  std::string title;  // drawn at the top when not empty
  // Also write a vector copy beside the PNG with vtkGL2PSExporter ("<path stem>.pdf" / ".svg" /
  // ".eps"); empty = none. Raster-only figures (particles, height map) are still raster inside.
  std::string vector_format;
};

// Axis-aligned box [lo, hi] in metres.
struct DomainBox {
  std::array<double, 3> lo{0, 0, 0};
  std::array<double, 3> hi{0, 0, 0};
};

// The spreader as drawn (SI), whatever its kind: its cross-section, a polygon (outline_x[k],
// outline_z[k]) in the x–z plane of the body frame, counter-clockwise, extruded along y over
// |y - y_centre| <= length / 2 (clipped to the domain's y extent; length 0: the whole extent),
// placed with the body frame's origin at `reference` and turned by `angle` about +y (right-hand
// rule, radians: +z turns towards +x, as for a wheel rolling forward). A body that `turns` is drawn
// with a red stripe along its length (on top at angle 0) and a red spoke on its front face, so that
// successive frames show it turning. No outline: nothing drawn.
struct SpreaderShape {
  std::vector<double> outline_x, outline_z;  // [m]
  std::array<double, 3> reference{0, 0, 0};  // [m]
  double y_centre = 0, length = 0;           // [m]
  double angle = 0;                          // [rad]
  bool turns = false;
};

struct SnapshotInput {
  std::vector<double> x, y, z, r;  // particle centres and radii [m]
  std::vector<double> speed;       // [m/s], coloured (drawn in mm/s)
  DomainBox domain;                      // the substrate is drawn at z = domain.lo[2]
  SpreaderShape spreader;
  double speed_max = 0;  // colour-bar top [m/s]; 0 = largest speed in the input
};

// Heights h[iy * nx + ix] [m] of cell (ix, iy) whose centre is origin + (ix + 1/2, iy + 1/2) * cell.
// NaN marks an empty cell (drawn grey).
struct HeightmapInput {
  int nx = 0, ny = 0;
  std::vector<double> height;
  std::array<double, 2> origin{0, 0};  // lower-left corner of the sampled region [m]
  std::array<double, 2> cell{0, 0};    // cell size in x and y [m]
};

// A quantity over the (U, omega) plane. `unit` is the SI unit: "m^2/s" (drawn mm^2/s), "m" (um),
// "m/s" (mm/s) or anything else (drawn as given).
struct PlottedQuantity {
  std::string name;  // "V_s", "R_q"
  std::string unit;  // SI
};

struct DesignPoint {
  double u = 0, omega = 0, value = 0;  // [m/s], [rad/s], SI of the quantity
  bool test = false;                   // test (held-out) sample, else training
};

// values[iw * u.size() + iu] is the prediction at (u[iu], omega[iw]).
struct SurfaceInput {
  PlottedQuantity quantity;
  std::vector<double> u, omega;  // grid axes, increasing [m/s], [rad/s]
  std::vector<double> values;
  std::vector<DesignPoint> points;  // simulated cases
};

struct ParityPanel {
  PlottedQuantity quantity;
  std::vector<double> train_simulated, train_predicted;  // SI
  std::vector<double> test_simulated, test_predicted;    // SI
  std::vector<double> cv_simulated, cv_predicted;        // SI, out-of-fold predictions of cross-validation
};

// One panel per output, side by side; Pearson R of each set is computed and shown in the legend.
struct ParityInput {
  std::vector<ParityPanel> panels;
};

struct MapPoint {
  double u = 0, omega = 0;  // [m/s], [rad/s]
};

struct OptimumMark {
  bool found = false;
  double u = 0, omega = 0;  // [m/s], [rad/s]
  double vs = 0, rq = 0;    // [m^2/s], [m]
  int verified = -1;        // -1: proposed only; 1: simulated inside its interval; 0: outside (verify stage)
  double probability = -1;  // P(R_q <= target), shown when >= 0
  double confidence = 0.5;  // the rule it was chosen by, shown above 0.5
};

// Fields over the (u, omega) grid, f[iw * u.size() + iu], SI units (V_s m^2/s, R_q m).
// rq_std / vs_std: model standard deviation, empty when the model gives none.
// Empty level lists are chosen automatically (about 8 round values over the field's range).
struct MapInput {
  std::vector<double> u, omega;
  std::vector<double> vs, rq;
  std::vector<double> vs_std, rq_std;
  std::vector<double> rq_levels, vs_levels, std_levels;  // SI
  std::vector<MapPoint> frontier;                        // efficient operating line
  std::vector<MapPoint> cases;                           // the simulated settings the model was trained on
  OptimumMark optimum;
  double rq_target = 0;  // [m], shown in the optimum label when > 0
  // Maps that cannot be trusted: drawn grey, and `notes` (one line each) printed over the plot.
  bool rq_greyed = false, vs_greyed = false;
  std::vector<std::string> notes;
};

// The speed-accuracy trade (tradeoff stage): one point per fidelity, errors in per cent of the
// reference's mean (signed; drawn as |error|), cost in any positive unit named by cost_label.
struct TradeoffPoint {
  std::string name;
  double cost = 0;                    // e.g. wall seconds per case
  double vs_error = 0, rq_error = 0;  // [%]
  bool reference = false;             // the reference: its cost is marked, it has no error
};
struct TradeoffInput {
  std::vector<TradeoffPoint> points;
  double vs_scatter = 0, rq_scatter = 0;  // heap-to-heap standard deviation of the reference [% of its mean]
  std::string cost_label = "wall time per case [s]";
};

void snapshot(const SnapshotInput& in, const std::filesystem::path& png, const Options& opt = {});
void heightmap(const HeightmapInput& in, const std::filesystem::path& png, const Options& opt = {});
void surface(const SurfaceInput& in, const std::filesystem::path& png, const Options& opt = {});
void parity(const ParityInput& in, const std::filesystem::path& png, const Options& opt = {});
void process_map(const MapInput& in, const std::filesystem::path& png, const Options& opt = {});
void tradeoff(const TradeoffInput& in, const std::filesystem::path& png, const Options& opt = {});

// frames[i] is written to directory / "<stem>_<i, 4 digits>.png"; the colour range is shared by all
// frames (largest speed over the sequence unless speed_max is set). Returns the files written.
std::vector<std::filesystem::path> animation_frames(const std::vector<SnapshotInput>& frames,
                                                    const std::filesystem::path& directory,
                                                    const std::string& stem = "frame", const Options& opt = {});

// True when this build can write vector copies (vtkGL2PSExporter present).
bool vector_output_available();

}  // namespace spreadmap::render
