// Layer metrics: host-only classes (virtuals allowed) behind the C descriptor. They run once per
// layer, not per contact. Arrays in, a JSON text of metrics out; the height map stays readable
// until the next evaluate() or destroy().
#pragma once
#include <spreadmap/abi.h>
#include <spreadmap/plugin.hpp>

#include <exception>
#include <stdexcept>

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

/* One metric a plugin gives: its column in metrics.csv, its SI unit, one line of meaning (ABI 10.2). */
typedef struct sm_metric_v1 {
  const char *name;
  const char *unit;
  const char *doc;
} sm_metric_v1;

typedef struct sm_metrics_ops_v1 {
  // Returns {"metrics": {name: value or null}, "units": {name: unit}, "warnings": [text]}; NULL on error.
  const char *(*evaluate)(void *self, const sm_layer_input_v1 *in, sm_error *err);
  // The height map of the last evaluate(), row-major (iy * nx + ix), heights above the substrate [m].
  const double *(*heightmap)(const void *self, uint32_t *nx, uint32_t *ny, double *x0, double *y0, double *cell);
#if SPREADMAP_TARGET_ABI_MINOR >= 2
  // The metrics every evaluate() gives, whatever the parameters (those a parameter switches on aside):
  // what a stage may count on before any layer is measured (10.2).
  const sm_metric_v1 *gives;
  uint32_t n_gives;
#endif
} sm_metrics_ops_v1;
}

namespace spreadmap {

// The height map of the last evaluate(); height null when there is none.
struct HeightMapView {
  uint32_t nx = 0, ny = 0;
  double x0 = 0, y0 = 0, cell = 0;
  const double *height = nullptr;
};

// The ops table of a metrics plugin, built from its class (SPREADMAP_METRICS_PLUGIN), which provides
//   const char *evaluate(const sm_layer_input_v1 &)   the JSON text above, valid until the next call
//   HeightMapView heightmap() const                   the last evaluate()'s map
//   static constexpr sm_metric_v1 gives[]             the metrics every evaluate() gives
// Exceptions never cross the C boundary: they become sm_error text.
template <class Self> struct MetricsGlue {
  static const char *evaluate(void *self, const sm_layer_input_v1 *in, sm_error *err) {
    try {
      if (!self || !in) throw std::invalid_argument("evaluate called without an instance or an input");
      return static_cast<Self *>(self)->evaluate(*in);
    } catch (const std::exception &e) {
      detail::set_error(err, e.what());
    } catch (...) {
      detail::set_error(err, "unknown exception while characterising the layer");
    }
    return nullptr;
  }
  static const double *heightmap(const void *self, uint32_t *nx, uint32_t *ny, double *x0, double *y0, double *cell) {
    const HeightMapView map = self ? static_cast<const Self *>(self)->heightmap() : HeightMapView{};
    const bool have = map.height != nullptr;
    if (nx) *nx = have ? map.nx : 0;
    if (ny) *ny = have ? map.ny : 0;
    if (x0) *x0 = have ? map.x0 : 0;
    if (y0) *y0 = have ? map.y0 : 0;
    if (cell) *cell = have ? map.cell : 0;
    return map.height;
  }
#if SPREADMAP_TARGET_ABI_MINOR >= 2
  static constexpr sm_metrics_ops_v1 table{&evaluate, &heightmap, Self::gives,
                                           static_cast<uint32_t>(sizeof(Self::gives) / sizeof(Self::gives[0]))};
#else
  static constexpr sm_metrics_ops_v1 table{&evaluate, &heightmap};
#endif
};

}  // namespace spreadmap

// The last line of a metrics plugin: SPREADMAP_METRICS_PLUGIN(Class, "name", "1.0.0", "summary").
#define SPREADMAP_METRICS_PLUGIN(CLASS, NAME, VERSION, SUMMARY) \
  SPREADMAP_PLUGIN("metrics", CLASS, NAME, VERSION, SUMMARY, &::spreadmap::MetricsGlue<CLASS>::table)
