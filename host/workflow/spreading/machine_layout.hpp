// The machine of scene.machine as walls: solid blocks (workflow/scene/block_wall.hpp) side by side
// along x, their tops the machine's floor, in the plates' frame (z = 0 the tops of the plates the
// spreader glides over, its gap measured from there):
//
//   x:  0 .. a          rear plate, top 0 (the spreader rests above it)
//       a .. b          reservoir: the piston, top -reservoir_depth + k x dosing x thickness
//       b .. c          transfer plate, top 0
//       c .. d          build well: the platform, top -k x thickness
//       d .. e          lip, top 0
//       e .. length     overflow: no floor; powder falls out through the domain's bottom (removed)
//
// for layer k (after its strokes). Across y the strip is periodic: the blocks span it. The blocks'
// faces that meet are vertical (a top face never meets a neighbour's top face in one plane while a
// sphere could rest on both), so no sphere is pushed twice at a seam.
#pragma once
#include <vector>

#include "workflow/scene/scene_spec.hpp"
#include "workflow/spreading/scene_model.hpp"

namespace spreadmap {

// The solid poured into the reservoir over its volume: poured powder packs at 0.55-0.64, so this
// overfills it, and levelling takes off the rest (machine_setup.hpp).
inline constexpr double reservoir_fill_packing = 0.64;

struct MachineLayout {
  double reservoir_from, reservoir_to, well_from, well_to, overflow_from;  // x [m]
  double thickness, dosing, reservoir_depth;                               // [m], [-], [m]
  double bottom;  // the domain's bottom z [m]: below the lowest platform and piston

  double platform_top(int layer) const { return -double(layer) * thickness; }
  double piston_top(int layer) const { return -reservoir_depth + double(layer) * dosing * thickness; }
  // The spreader's lower edge above the platform while it spreads layer k [m] (gap: its gap above the
  // plates).
  double edge_above_platform(double gap, int layer) const { return gap - platform_top(layer); }
};

// The layout of `scene` (which has a machine), its domain's bottom below the deepest platform and
// piston by two of the powder's largest diameters.
MachineLayout machine_layout(const Scene &scene);

// The machine's blocks for layer k = scene.machine->layer: at rest in layer k's places, or, with
// `strokes`, the platform and piston starting from layer k - 1's places and moving into layer k's at
// stroke_speed from time 0. The blocks' contact law is the substrate's.
std::vector<scene::WallSpec> machine_walls(const Scene &scene, bool strokes);

// How long the longer of the two strokes takes [s].
double stroke_time(const Scene &scene);

// Below which z the buried powder may sleep during a pass (time.sleep, machine.sleep_depth > 0):
// sleep_depth below the fresh layer's bottom, the plates' level less one layer, over the well and
// the reservoir alike. -infinity: no sphere sleeps by depth (no machine, or sleep_depth 0).
double sleep_below(const Scene &scene);

}  // namespace spreadmap
