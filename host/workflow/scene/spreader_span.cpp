#include "workflow/scene/spreader_span.hpp"

#include <fmt/format.h>

namespace spreadmap {

std::optional<SpanShortfall> spreader_span_shortfall(const sm_spreader_description_v2 &spreader,
                                                     const engine::Domain &domain) {
  if (!(spreader.length > 0)) return std::nullopt;  // unbounded along y
  const double lo = domain.lo[1], hi = domain.hi[1], width = hi - lo;
  const double from = spreader.y_centre - 0.5 * spreader.length, to = spreader.y_centre + 0.5 * spreader.length;
  const double slack = 1e-9 * width;  // a spreader written as exactly the width spans it
  if (from <= lo + slack && to >= hi - slack) return std::nullopt;
  SpanShortfall s;
  s.periodic = domain.periodic[1];
  s.what = fmt::format("the spreader spans y = {:g}..{:g} mm, the domain {:g}..{:g} mm{}", from * 1e3, to * 1e3,
                       lo * 1e3, hi * 1e3,
                       s.periodic ? ", periodic: the powder beyond its end is never spread, and a sphere that "
                                    "crosses the seam beside its end face appears inside it"
                                  : ": the powder beyond its ends is never spread");
  const double centre = 0.5 * (lo + hi);
  s.fix = spreader.length >= width - slack
              ? fmt::format("set spreader.y_centre: {:g} mm (the middle of the width)", centre * 1e3)
              : fmt::format("make spreader.length at least {:g} mm and set spreader.y_centre: {:g} mm", width * 1e3,
                            centre * 1e3);
  return s;
}

}  // namespace spreadmap
