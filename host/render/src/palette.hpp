// Colour maps used by the figures, as piecewise-linear control points (perceptual where it
// matters: viridis for heights and predictions; a rainbow for particle speed, as DEM pictures use;
// yellow-orange-red bands for roughness on the process map: red reads as "rough").
#pragma once

#include "figure.hpp"

#include <vtkSmartPointer.h>

class vtkLookupTable;

namespace spreadmap::render::detail {

enum class ColourMap { viridis, rainbow, yellow_red };

Rgb colour_at(ColourMap map, double t);  // t in [0, 1], clamped
// A 256-entry table over [lo, hi]; out-of-range values take the end colours, NaN is light grey.
vtkSmartPointer<vtkLookupTable> make_lookup_table(ColourMap map, double lo, double hi, int entries = 256);

}  // namespace spreadmap::render::detail
