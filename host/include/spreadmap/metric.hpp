// Layer metrics: host-only classes (virtuals allowed) behind the C descriptor. They run once per
// layer, not per contact. Arrays in, a JSON text of metrics out; the height map stays readable
// until the next evaluate() or destroy().
#pragma once
#include <spreadmap/abi.h>
#include <spreadmap/plugin.hpp>

extern "C" {
typedef struct sm_layer_input_v1 {
  uint64_t n;                   // spheres
  const double *x, *y, *z, *r;  // centres and radii [m]
  double region[4];             // x0, x1, y0, y1 of the sampling rectangle [m]
  double substrate_z;           // height of the substrate plane [m]
  double periodic_y[2];         // y_lo, y_hi of a periodic strip; equal values = not periodic
  double speed;                 // spreader speed U [m/s] for V_s; NaN when unknown
  double gap;                   // spreader gap [m] for packing over the gap; NaN when unknown
  // 1: sphere i belongs to the substrate (a rough substrate's fixed spheres): ground the powder may
  // rest on, never part of the layer. NULL: every sphere is powder (ABI 8).
  const uint8_t *substrate;
} sm_layer_input_v1;

typedef struct sm_metrics_ops_v1 {
  // Returns {"metrics": {name: value or null}, "units": {name: unit}, "warnings": [text]}; NULL on error.
  const char *(*evaluate)(void *self, const sm_layer_input_v1 *in, sm_error *err);
  // The height map of the last evaluate(), row-major (iy * nx + ix), heights above the substrate [m].
  const double *(*heightmap)(const void *self, uint32_t *nx, uint32_t *ny, double *x0, double *y0, double *cell);
} sm_metrics_ops_v1;
}
