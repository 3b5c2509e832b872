#include "powder/coverage.hpp"

#include <fmt/format.h>

#include "powder/powder_error.hpp"

namespace spreadmap::powder {

LayerCoverage sampled_length_check(double solid_volume, double layer_thickness, double width, double required_length,
                                   double packing) {
  if (!(layer_thickness > 0) || !(width > 0) || !(packing > 0 && packing <= 1))
    throw PowderError(
        fmt::format("sampled_length_check: thickness {} m and width {} m must be > 0 and packing {} in (0, 1]",
                    layer_thickness, width, packing));
  const double length = solid_volume / (packing * layer_thickness * width);
  return {length, required_length, length >= required_length};
}

}  // namespace spreadmap::powder
