// Whether a spreader spans the domain's width. A spreader geometry sees no periodic images, so across
// a periodic width one shorter than the width leaves powder that is never spread, and a sphere that
// crosses the seam beside its end face appears inside it (an overlap of a large part of its diameter:
// the run stops with a blow-up). With open sides the powder beyond its ends is only never spread.
#pragma once
#include <spreadmap/geometry.hpp>

#include <optional>
#include <string>

#include "engine/domain.hpp"

namespace spreadmap {

struct SpanShortfall {
  bool periodic = false;  // across a periodic width: refused; open sides: a warning
  std::string what;       // the spreader's extent against the width's
  std::string fix;
};

// Empty when the spreader (its description's y_centre and length; length 0: unbounded) covers the
// domain's y extent.
std::optional<SpanShortfall> spreader_span_shortfall(const sm_spreader_description_v2 &spreader,
                                                     const engine::Domain &domain);

}  // namespace spreadmap
